// brdfbake's CSV text, read in one place: "# key: value" description lines, a header of column
// names, then rows of comma-separated cells (io's write_table writes it). read_table's CSV reader
// (host/io/table_read.cpp), the sheen-ltc model's tables (models/sheen_ltc_table.cpp: an embedded
// default or a file) and the embedded CIE data (models/spectrum.cpp) split their text here; each
// checks the numbers and names its own mistakes. It sits in models, the lowest layer its users
// share (io is above models). Blank lines are skipped; a row is read when asked for, so
// a large table's cells are never all held at once.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace brdfbake {

/// The comma-separated cells of one line ("a,b" -> {"a", "b"}; a trailing comma adds no cell).
std::vector<std::string> csv_cells(const std::string& line);

/// A CSV text's description and header, and its rows one at a time. The text must outlive it.
class CsvText {
public:
    /// Reads the description lines and the header (the first other line that is not blank).
    explicit CsvText(const std::string& text);

    const std::map<std::string, std::string>& description() const { return description_; }
    /// The description's value of `key`, or "" where it has none.
    std::string said(const std::string& key) const;
    const std::vector<std::string>& columns() const { return columns_; }
    /// The index of the column named `name`, or -1.
    int column(const std::string& name) const;
    /// The next row's cells into `cells`; false after the last row.
    bool next_row(std::vector<std::string>& cells);

private:
    bool next_line(std::string& line);

    const std::string& text_;
    size_t pos_ = 0;
    std::map<std::string, std::string> description_;
    std::vector<std::string> columns_;
};

}  // namespace brdfbake

#include "models/csv_text.h"

namespace brdfbake {

std::vector<std::string> csv_cells(const std::string& line) {
    std::vector<std::string> cells;
    size_t start = 0;
    while (start < line.size()) {
        const size_t comma = line.find(',', start);
        const size_t end = comma == std::string::npos ? line.size() : comma;
        cells.push_back(line.substr(start, end - start));
        start = end + 1;
    }
    return cells;
}

CsvText::CsvText(const std::string& text) : text_(text) {
    for (std::string line; next_line(line);) {
        if (line.rfind("# ", 0) != 0) {
            columns_ = csv_cells(line);
            return;
        }
        const size_t colon = line.find(": ");
        if (colon != std::string::npos) description_[line.substr(2, colon - 2)] = line.substr(colon + 2);
    }
}

std::string CsvText::said(const std::string& key) const {
    const auto it = description_.find(key);
    return it == description_.end() ? std::string() : it->second;
}

int CsvText::column(const std::string& name) const {
    for (size_t i = 0; i < columns_.size(); ++i)
        if (columns_[i] == name) return int(i);
    return -1;
}

bool CsvText::next_row(std::vector<std::string>& cells) {
    std::string line;
    if (!next_line(line)) return false;
    cells = csv_cells(line);
    return true;
}

bool CsvText::next_line(std::string& line) {
    while (pos_ < text_.size()) {
        const size_t newline = text_.find('\n', pos_);
        const size_t end = newline == std::string::npos ? text_.size() : newline;
        line.assign(text_, pos_, end - pos_);
        pos_ = end + 1;
        if (!line.empty()) return true;
    }
    return false;
}

}  // namespace brdfbake

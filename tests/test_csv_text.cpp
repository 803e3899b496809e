// The one reader of brdfbake's CSV text (models/csv_text.h), which read_table's CSV reader and
// the sheen-ltc tables share: checked against texts written here by hand, cell by cell.
#include <catch2/catch.hpp>

#include "models/csv_text.h"

using namespace brdfbake;

TEST_CASE("csv text: description, header and rows, blank lines skipped", "[io][csv]") {
    const std::string text =
        "# kind: albedo\n# x_range: 0 1\n#not a description\n\nmu,E,error\n0.5,0.25,1e-3\n\n1,,2\n3,4,\n";
    CsvText t(text);
    CHECK(t.description().size() == 2);
    CHECK(t.said("kind") == "albedo");
    CHECK(t.said("x_range") == "0 1");
    CHECK(t.said("y_axis").empty());
    // "#not..." is the first line that is not a "# key: value" line: the header.
    REQUIRE(t.columns() == std::vector<std::string>{"#not a description"});
    CHECK(t.column("mu") == -1);
    std::vector<std::string> cells;
    REQUIRE(t.next_row(cells));
    CHECK(cells == std::vector<std::string>{"mu", "E", "error"});
    REQUIRE(t.next_row(cells));
    CHECK(cells == std::vector<std::string>{"0.5", "0.25", "1e-3"});
    REQUIRE(t.next_row(cells));
    CHECK(cells == std::vector<std::string>{"1", "", "2"});
    REQUIRE(t.next_row(cells));
    CHECK(cells == std::vector<std::string>{"3", "4"});  // a trailing comma adds no cell
    CHECK_FALSE(t.next_row(cells));
    CHECK_FALSE(t.next_row(cells));
}

TEST_CASE("csv text: the columns are found by name, a text without rows has none", "[io][csv]") {
    const std::string text = "# kind: sheen-ltc\nmu,roughness,a,b,R,error";
    CsvText t(text);
    CHECK(t.column("mu") == 0);
    CHECK(t.column("R") == 4);
    CHECK(t.column("error") == 5);
    CHECK(t.column("r") == -1);
    std::vector<std::string> cells;
    CHECK_FALSE(t.next_row(cells));
    const std::string empty;
    CsvText e(empty);
    CHECK(e.columns().empty());
    CHECK(e.description().empty());
    CHECK(csv_cells("") == std::vector<std::string>{});
    CHECK(csv_cells(",a") == std::vector<std::string>{"", "a"});
}

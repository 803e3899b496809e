#include "brdfbake/output.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "brdfbake/error.h"
#include "brdfbake/spec.h"

namespace brdfbake {

Format parse_format(const std::string& text) {
    if (text == "table") return Format::Table;
    if (text == "json") return Format::Json;
    if (text == "csv") return Format::Csv;
    throw Error("unknown format '" + text + "'; expected table, json or csv");
}

void write_file_atomically(const std::string& path, const std::string& content) {
    const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw Error("cannot write '" + path + "': " + std::strerror(errno));
        out << content;
        out.flush();
        if (!out) {
            std::remove(tmp.c_str());
            throw Error("cannot write '" + path + "': " + std::strerror(errno));
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        throw Error("cannot write '" + path + "': " + why);
    }
}

void emit(const std::string& path, const std::string& content) {
    if (path.empty() || path == "-") {
        std::cout << content << std::flush;
        return;
    }
    write_file_atomically(path, content);
}

std::vector<double> parse_number_list(const std::string& text, const std::string& what) {
    std::vector<double> out;
    size_t start = 0;
    while (start <= text.size()) {
        size_t comma = text.find(',', start);
        if (comma == std::string::npos) comma = text.size();
        out.push_back(parse_number(text.substr(start, comma - start), what));
        start = comma + 1;
    }
    return out;
}

}  // namespace brdfbake

#include "brdfbake/memory_limit.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "brdfbake/error.h"

namespace brdfbake {

namespace {

std::uint64_t g_limit = 0;  // 0: the default

std::uint64_t default_limit() {
    if (const char* env = std::getenv("BRDFBAKE_MAX_MEMORY"); env && *env) {
        try {
            return parse_memory_size(env);
        } catch (const Error& e) {
            throw Error(std::string("BRDFBAKE_MAX_MEMORY: ") + e.what());
        }
    }
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    std::uint64_t limit = pages > 0 && page > 0 ? std::uint64_t(pages) * std::uint64_t(page) / 2
                                                : std::uint64_t(4) << 30;
    return limit;
}

}  // namespace

std::uint64_t memory_limit() {
    std::uint64_t limit = g_limit ? g_limit : default_limit();
    // An address-space limit (ulimit -v) leaves room for the program, OpenCL and PoCL themselves.
    struct rlimit rl {};
    if (::getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        limit = std::min<std::uint64_t>(limit, std::uint64_t(rl.rlim_cur) / 5 * 4);
    return limit;
}

void set_memory_limit(std::uint64_t bytes) { g_limit = bytes; }

std::string memory_size_words(double bytes) {
    const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 5) {
        bytes /= 1024.0;
        ++u;
    }
    char text[64];
    if (u == 0)
        std::snprintf(text, sizeof text, "%.0f bytes", bytes);
    else if (bytes == std::floor(bytes) || bytes >= 100)
        std::snprintf(text, sizeof text, "%.0f %s", bytes, units[u]);
    else
        std::snprintf(text, sizeof text, bytes < 10 ? "%.2f %s" : "%.1f %s", bytes, units[u]);
    return text;
}

void check_memory(double bytes, const std::string& what) {
    const std::uint64_t limit = memory_limit();
    if (!(bytes <= double(limit)))
        throw Error(what + " needs about " + memory_size_words(bytes) + " of memory; the limit is " +
                    memory_size_words(double(limit)) + " (raise it with --max-memory or BRDFBAKE_MAX_MEMORY)");
}

std::uint64_t parse_memory_size(const std::string& text) {
    const std::string bad = "'" + text + "' is not a memory size (e.g. 4G, 512M, 2000000000)";
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end == text.c_str() || !std::isfinite(v) || !(v > 0.0)) throw Error(bad);
    std::string unit(end);
    double scale = 1.0;
    if (!unit.empty()) {
        const char c = char(std::toupper(static_cast<unsigned char>(unit[0])));
        const std::string prefixes = "KMGT";
        const size_t p = prefixes.find(c);
        if (p != std::string::npos) {
            scale = std::pow(1024.0, double(p + 1));
            unit.erase(0, 1);
        }
        if (unit == "iB" || unit == "B" || unit == "b") unit.clear();
        if (!unit.empty()) throw Error(bad);
    }
    const double bytes = v * scale;
    if (!(bytes >= 1.0) || bytes > 1.8e19) throw Error(bad);
    return std::uint64_t(bytes);
}

}  // namespace brdfbake

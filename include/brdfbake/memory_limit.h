// The memory a run may take, judged before anything is allocated: every computation that
// allocates in proportion to its input (cells x samples, point tables, device buffers) asks
// check_memory() with its estimate first, and a request over the limit is refused with one
// line naming the need, the limit and how to raise it.
#pragma once

#include <cstdint>
#include <string>

namespace brdfbake {

/// The limit in bytes: set_memory_limit()'s value if one was set, else $BRDFBAKE_MAX_MEMORY if set
/// (parsed by parse_memory_size), else half the machine's physical memory; never more than 80% of
/// the address-space limit (`ulimit -v`) when one is set.
std::uint64_t memory_limit();

/// Sets the limit for this process (the CLI's --max-memory). 0 restores the default.
void set_memory_limit(std::uint64_t bytes);

/// Throws Error if `bytes` exceeds memory_limit(): "<what> needs about 6.4 GB of memory; the limit
/// is 4 GB (raise it with --max-memory or BRDFBAKE_MAX_MEMORY)".
void check_memory(double bytes, const std::string& what);

/// "4G", "512M", "64k", "1.5GiB", "2000000000": a size in bytes (k, M, G, T are powers of 1024;
/// an optional trailing "B" or "iB"). Throws Error on anything else, 0 or a negative size.
std::uint64_t parse_memory_size(const std::string& text);

/// "6.4 GB", "512 MB": a size for messages (powers of 1024, written as GB/MB/kB).
std::string memory_size_words(double bytes);

}  // namespace brdfbake

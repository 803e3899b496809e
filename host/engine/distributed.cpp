#include "engine/distributed.h"

#include <cstdlib>
#include <new>

#include "brdfbake/engine.h"

namespace brdfbake::dist {
namespace {

World* g_world = nullptr;
bool g_failure_known = false;  // a JobFailure was thrown or reported: no further steps

// A step's contribution: 'V' and the payload, or 'E', the exit status, a newline and the message.
Error failure_of(const std::vector<std::string>& all, bool& any) {
    any = false;
    int first = -1, failed = 0;
    for (size_t r = 0; r < all.size(); ++r)
        if (!all[r].empty() && all[r][0] == 'E') {
            ++failed;
            if (first < 0) first = int(r);
        }
    if (first < 0) return Error("");
    any = true;
    const std::string& e = all[size_t(first)];
    const size_t nl = e.find('\n');
    const int code = std::atoi(e.substr(1, nl - 1).c_str());
    std::string message = nl == std::string::npos ? std::string() : e.substr(nl + 1);
    // A failure every rank saw alike (bad input) reads as in one process; else name the rank.
    if (failed < int(all.size()))
        message = "rank " + std::to_string(first) + " of " + std::to_string(all.size()) + ": " + message;
    return Error(message, code == 0 ? kExitError : code);
}

}  // namespace

void set_world(World* world) {
    g_world = world;
    g_failure_known = false;
}

int rank() { return g_world ? g_world->rank() : 0; }
int size() { return g_world ? g_world->size() : 1; }
bool active() { return size() > 1; }
bool is_writer() { return rank() == 0; }

std::vector<std::string> exchange(const std::string& payload) {
    if (!active()) return {payload};
    std::vector<std::string> all = g_world->allgather("V" + payload);
    bool any = false;
    const Error failure = failure_of(all, any);
    if (any) {
        g_failure_known = true;
        throw JobFailure(failure.what(), failure.exit_code());
    }
    for (std::string& p : all) p.erase(0, 1);
    return all;
}

void agree() { exchange(std::string()); }

Error describe_failure(std::exception_ptr failure) {
    try {
        std::rethrow_exception(failure);
    } catch (const Error& e) {
        return e;
    } catch (const cl::Error& e) {
        return Error(std::string("OpenCL call ") + e.what() + " failed: " + cl_error_name(e.err()));
    } catch (const std::bad_alloc&) {
        return Error("out of host memory (try a smaller table or fewer samples)");
    } catch (const std::exception& e) {
        return Error(e.what());
    } catch (...) {
        return Error("unknown failure");
    }
}

Error report_failure(const Error& failure) {
    if (!active() || g_failure_known) return failure;
    g_failure_known = true;
    const std::vector<std::string> all =
        g_world->allgather("E" + std::to_string(failure.exit_code()) + "\n" + failure.what());
    bool any = false;
    return failure_of(all, any);
}

}  // namespace brdfbake::dist

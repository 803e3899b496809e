// Errors that reach the user. Library code throws; only main() turns them into exit codes.
#pragma once

#include <stdexcept>
#include <string>

namespace brdfbake {

/// Exit statuses of the command line: 0 success, 1 a violation found by `check`,
/// 2 bad input or a fault (no device, build failure, unwritable file, ...).
enum ExitCode : int { kExitOk = 0, kExitViolation = 1, kExitError = 2 };

/// An error with a message meant for the user and the exit status it maps to.
class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message, int exit_code = kExitError)
        : std::runtime_error(message), exit_code_(exit_code) {}
    int exit_code() const { return exit_code_; }

private:
    int exit_code_;
};

}  // namespace brdfbake

// The output folder of `brdfbake bake`: created only for this bake and removed again if the bake
// fails before it wrote anything, locked so that two bakes into one folder run one after the
// other, and the content hash that lets the index and its tables be checked against each other.
// docs/scenes.md ("Bake folders") documents the behaviour.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace brdfbake {

/// The name of the content-hash algorithm recorded in a bake's index.json.
extern const char* const kContentHashAlgorithm;  // "CRC-64/XZ"

/// CRC-64/XZ (the CRC of the XZ file format: polynomial 0x42F0E1EBA9EA3693, reflected, initial
/// value and final XOR all ones; catalogue check value 0x995DC9BBDF1939FA for "123456789") of
/// `bytes`, through Boost.CRC. It detects a table file that is not the one the index describes
/// (another bake's, a truncated or edited file); it is not a defence against a forged file.
std::uint64_t crc64_xz(const std::string& bytes);

/// The content hash of a file as the index records it: 16 lowercase hex digits. Throws Error when
/// the file cannot be read.
std::string content_hash_of_file(const std::string& path);

/// A bake's output folder, held for the lifetime of the object.
///
/// The constructor creates the folder (and missing parents) and takes an exclusive flock(2) on
/// `FOLDER/.brdfbake.lock`. When another bake holds it, it says so once on stderr and waits up to
/// `wait_seconds` (0: not at all), then throws Error. The lock file is removed when the object
/// goes away (the lock protocol re-checks the file after locking, so removing it is safe).
/// Unless commit() was called, the destructor also removes the folders this object created,
/// if they are empty: a bake that fails before writing leaves nothing behind.
class BakeFolder {
public:
    BakeFolder(const std::string& folder, double wait_seconds);
    ~BakeFolder();
    BakeFolder(const BakeFolder&) = delete;
    BakeFolder& operator=(const BakeFolder&) = delete;

    /// Something was written into the folder: keep it. (Without it the destructor still removes
    /// only empty folders.)
    void commit() { committed_ = true; }
    const std::string& path() const { return folder_; }
    static const char* lock_name() { return ".brdfbake.lock"; }

private:
    std::string folder_;
    std::string lock_path_;
    std::vector<std::string> created_;  // folders this object created, outermost first
    int fd_ = -1;
    bool committed_ = false;
};

}  // namespace brdfbake

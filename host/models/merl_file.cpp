#include "models/merl_file.h"

#include <fcntl.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <mutex>

#include "brdfbake/brdf/model_registry.h"
#include "brdfbake/error.h"
#include "models/input_file.h"

namespace brdfbake {

namespace {

constexpr double kPi = 3.14159265358979323846;
const char* const kBuiltinLambert = "builtin:lambert";

bool little_endian() {
    const std::uint16_t one = 1;
    unsigned char b;
    std::memcpy(&b, &one, 1);
    return b == 1;
}

template <typename T>
T read_le(const char* p) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, p, sizeof(T));
    if (!little_endian())
        for (size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(bytes[k], bytes[sizeof(T) - 1 - k]);
    T v;
    std::memcpy(&v, bytes, sizeof(T));
    return v;
}

template <typename T>
void append_le(std::string& out, T v) {
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    if (!little_endian())
        for (size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(bytes[k], bytes[sizeof(T) - 1 - k]);
    out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

const char* channel_name(MerlChannel c) {
    static const char* names[] = {"r", "g", "b", "y"};
    return names[int(c)];
}

/// A validated file version, read into memory (pread: a file truncated or rewritten while in use
/// changes nothing here, where a mapping would raise SIGBUS on the lost pages) and known by its
/// identity (device, inode, size, modification time): a file rewritten in place is a new version.
/// A file rewritten within one timestamp tick of its read keeps its identity: such a version is
/// "racy" (git's word for it, Documentation/technical/racy-git.txt) and its bytes are compared
/// again at the next use, until a read starts a tick after the modification time.
struct FileVersion {
    std::string path;
    dev_t dev = 0;
    ino_t ino = 0;
    std::int64_t mtime_ns = 0;
    std::int64_t read_ns = 0;  // the wall clock when its last read began
    bool builtin = false;      // builtin:lambert (no bytes)
    std::vector<char> bytes;   // kMerlFileBytes
};

struct Store {
    std::mutex mutex;
    std::deque<FileVersion> files;
    std::deque<std::vector<double>> tables;  // a deque: a table never moves once stored
    std::vector<MerlTableInfo> info;
    std::vector<size_t> table_file;  // per table, its file in `files`
};

/// A parsed spec written back: name:key=value,...
std::string spec_text(const Spec& s) {
    std::string out = s.name;
    for (size_t k = 0; k < s.keys.size(); ++k) out += (k ? "," : ":") + s.keys[k].first + "=" + s.keys[k].second;
    return out;
}

Store& store() {
    static Store s;
    return s;
}

}  // namespace

namespace {

/// The dimensions of a MERL file's first 12 bytes: refused unless 90 x 90 x 180.
void check_dims(const char* bytes, const std::string& what, const std::string& path) {
    const std::int32_t dims[3] = {read_le<std::int32_t>(bytes), read_le<std::int32_t>(bytes + 4),
                                  read_le<std::int32_t>(bytes + 8)};
    if (dims[0] != BB_MERL_THETA_H || dims[1] != BB_MERL_THETA_D || dims[2] != BB_MERL_PHI_D)
        throw Error(what + " '" + path + "' has dimensions " + std::to_string(dims[0]) + " x " +
                    std::to_string(dims[1]) + " x " + std::to_string(dims[2]) + "; a MERL file has 90 x 90 x 180");
}

/// Refuses a path that is not a regular file of exactly kMerlFileBytes with the error naming why.
/// The size is judged before a byte is read (read_input_file refuses a larger file, a directory
/// or a device); a smaller one is refused after the read, with its size.
[[noreturn]] void refuse(const std::string& path, const std::string& what) {
    const std::string bytes = read_input_file(path, what, kMerlFileBytes);
    if (bytes.size() < 12)
        throw Error(what + " '" + path + "' is " + std::to_string(bytes.size()) +
                    " bytes: too short for the three int32 dimensions of a MERL file");
    check_dims(bytes.data(), what, path);
    throw Error(what + " '" + path + "' is " + std::to_string(bytes.size()) + " bytes; a MERL file of 90 x 90 x 180 "
                "bins has " + std::to_string(kMerlFileBytes) + " (truncated?)");
}

/// The coarsest modification-time tick of the file systems in use (FAT's 2 s; ext4 and tmpfs stamp
/// from the kernel's coarse clock, a few ms): a version whose mtime lies within it of its read is
/// racy (FileVersion).
constexpr std::int64_t kTimestampTickNs = 2000000000;

std::int64_t wall_ns() {
    struct timespec t {};
    ::clock_gettime(CLOCK_REALTIME, &t);
    return std::int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}

/// Every byte of the open file `fd` (kMerlFileBytes), by pread; a file that shrinks meanwhile is
/// an Error naming it.
std::vector<char> read_all(int fd, const std::string& what, const std::string& path) {
    std::vector<char> out(kMerlFileBytes);
    size_t got = 0;
    while (got < out.size()) {
        const ssize_t n = ::pread(fd, out.data() + got, out.size() - got, off_t(got));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw Error("cannot read " + what + " '" + path + "': " + std::strerror(errno));
        if (n == 0)
            throw Error(what + " '" + path + "' was truncated while it was read (" + std::to_string(got) + " of " +
                        std::to_string(kMerlFileBytes) + " bytes)");
        got += size_t(n);
    }
    return out;
}

/// Refuses bytes whose dimensions are not 90 x 90 x 180 or that hold a NaN or an Inf.
void validate(const std::vector<char>& bytes, const std::string& what, const std::string& path) {
    check_dims(bytes.data(), what, path);
    for (int c = 0; c < 3; ++c) {
        const char* plane = bytes.data() + 12 + size_t(c) * BB_MERL_BINS * 8;
        for (size_t i = 0; i < BB_MERL_BINS; ++i) {
            const double v = read_le<double>(plane + 8 * i);
            if (!std::isfinite(v))
                throw Error(what + " '" + path + "' holds a non-finite value (" + std::string(std::isnan(v) ? "NaN" : "Inf") +
                            ") in the " + channel_name(MerlChannel(c)) + " plane at bin " + std::to_string(i));
        }
    }
}

/// Reads and validates the file at `path` (dimensions, every value finite), once per process and
/// file version: a second channel of the same version reads the same bytes; a racy version
/// (FileVersion) is read again and compared, a changed one stored as a new version.
size_t open_file(Store& s, const std::string& path) {
    const std::string what = "MERL file";
    FileVersion m;
    m.path = path;
    if (path == kBuiltinLambert) {
        for (size_t k = 0; k < s.files.size(); ++k)
            if (s.files[k].path == path && s.files[k].builtin) return k;
        m.builtin = true;
        s.files.push_back(m);
        return s.files.size() - 1;
    }
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    struct stat st {};
    if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || std::uintmax_t(st.st_size) != kMerlFileBytes) {
        if (fd >= 0) ::close(fd);
        refuse(path, what);
    }
    m.dev = st.st_dev;
    m.ino = st.st_ino;
    m.mtime_ns = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    m.read_ns = wall_ns();
    size_t same = s.files.size();  // the stored version of this identity, if any
    for (size_t k = 0; k < s.files.size() && same == s.files.size(); ++k) {
        const FileVersion& f = s.files[k];
        if (!f.bytes.empty() && f.path == path && f.dev == m.dev && f.ino == m.ino && f.mtime_ns == m.mtime_ns) same = k;
    }
    if (same < s.files.size() && s.files[same].mtime_ns + kTimestampTickNs < s.files[same].read_ns) {
        ::close(fd);
        return same;
    }
    try {
        m.bytes = read_all(fd, what, path);
    } catch (...) {
        ::close(fd);
        throw;
    }
    ::close(fd);
    if (same < s.files.size() && m.bytes == s.files[same].bytes) {  // racy, and unchanged
        s.files[same].read_ns = m.read_ns;
        return same;
    }
    validate(m.bytes, what, path);
    // One version's bytes per path: an older version's tables stay, its bytes go (a later use of
    // that identity, were it to come back, reads the file again).
    for (FileVersion& f : s.files)
        if (f.path == path) std::vector<char>().swap(f.bytes);
    s.files.push_back(std::move(m));
    return s.files.size() - 1;
}

/// One channel of a file, scaled ([M03]); Rec. 709 luminance for y (ITU-R BT.709-6, item 3.2),
/// unmeasured where any colour is. Built straight from the file's bytes, one pass.
std::vector<double> channel_table(const FileVersion& f, MerlChannel channel) {
    if (f.builtin) return std::vector<double>(BB_MERL_BINS, 1.0 / kPi);  // builtin:lambert
    std::vector<double> t(BB_MERL_BINS);
    const auto plane = [&](int c) { return f.bytes.data() + 12 + size_t(c) * BB_MERL_BINS * 8; };
    if (channel != MerlChannel::Y) {
        const int c = int(channel);
        const char* p = plane(c);
        for (size_t i = 0; i < t.size(); ++i) {
            const double v = read_le<double>(p + 8 * i);
            t[i] = v < 0.0 ? -1.0 : v * kMerlScale[size_t(c)];
        }
        return t;
    }
    const char *pr = plane(0), *pg = plane(1), *pb = plane(2);
    for (size_t i = 0; i < t.size(); ++i) {
        const double r = read_le<double>(pr + 8 * i), g = read_le<double>(pg + 8 * i), b = read_le<double>(pb + 8 * i);
        t[i] = r < 0 || g < 0 || b < 0
                   ? -1.0
                   : 0.2126 * (r * kMerlScale[0]) + 0.7152 * (g * kMerlScale[1]) + 0.0722 * (b * kMerlScale[2]);
    }
    return t;
}

}  // namespace

void merl_node_dirs(int ih, int id, int ip, std::array<double, 3>& wo, std::array<double, 3>& wi) {
    // The nodes (brdf/merl.h): theta_h = (ih/90)^2 pi/2, theta_d = id pi/180, phi_d = ip pi/180.
    const double th = double(ih) * ih / (double(BB_MERL_THETA_H) * BB_MERL_THETA_H) * kPi / 2;
    const double td = double(id) / BB_MERL_THETA_D * kPi / 2, pd = double(ip) / BB_MERL_PHI_D * kPi;
    const double d[3] = {std::sin(td) * std::cos(pd), std::sin(td) * std::sin(pd), std::cos(td)};
    // wi = R_z(phi_h) R_y(theta_h) d with phi_h = 0 [R98]; wo the reflection of wi about h.
    const double h[3] = {std::sin(th), 0.0, std::cos(th)};
    wi = {d[0] * std::cos(th) + d[2] * std::sin(th), d[1], -d[0] * std::sin(th) + d[2] * std::cos(th)};
    const double c = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
    for (int k = 0; k < 3; ++k) wo[k] = 2 * c * h[k] - wi[k];
}

void write_merl_file(const std::string& path,
                     const std::function<std::array<double, 3>(const std::array<double, 3>& wo,
                                                               const std::array<double, 3>& wi)>& f) {
    std::vector<std::array<double, 3>> values(BB_MERL_BINS);
    for (int ih = 0; ih < BB_MERL_THETA_H; ++ih)
        for (int id = 0; id < BB_MERL_THETA_D; ++id)
            for (int ip = 0; ip < BB_MERL_PHI_D; ++ip) {
                std::array<double, 3> wo, wi;
                merl_node_dirs(ih, id, ip, wo, wi);
                values[bb_merl_index(ih, id, ip)] = f(wo, wi);
            }
    std::string out;
    out.reserve(kMerlFileBytes);
    for (std::int32_t dim : {BB_MERL_THETA_H, BB_MERL_THETA_D, BB_MERL_PHI_D}) append_le<std::int32_t>(out, dim);
    for (int c = 0; c < 3; ++c)
        for (const auto& v : values) append_le<double>(out, v[c] < 0.0 ? -1.0 : v[c] / kMerlScale[c]);
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(out.data(), std::streamsize(out.size()));
    if (!file) throw Error("cannot write MERL file '" + path + "'");
}

/// Whether phi_d nodes k and 180 - k (the mirror image of a pair, brdf/merl.h) agree in every
/// row: both unmeasured, or within 1e-9 relative (a file written from a symmetric model by
/// another program's trigonometry differs in the last bits).
static bool table_mirror_symmetric(const std::vector<double>& t) {
    for (int ih = 0; ih < BB_MERL_THETA_H; ++ih)
        for (int id = 0; id < BB_MERL_THETA_D; ++id)
            for (int k = 1; k < BB_MERL_PHI_D / 2; ++k) {
                const double a = t[size_t(bb_merl_index(ih, id, k))], b = t[size_t(bb_merl_index(ih, id, BB_MERL_PHI_D - k))];
                if ((a < 0) != (b < 0)) return false;
                if (a >= 0 && std::fabs(a - b) > 1e-9 * std::max(std::fabs(a), std::fabs(b))) return false;
            }
    return true;
}

int merl_table_index(const std::string& path, MerlChannel channel) {
    Store& s = store();
    std::lock_guard<std::mutex> lock(s.mutex);
    const size_t file = open_file(s, path);  // once per file (path, inode, size, mtime)
    for (size_t k = 0; k < s.info.size(); ++k)
        if (s.table_file[k] == file && s.info[k].channel == channel) return int(k);
    std::vector<double> t = channel_table(s.files[file], channel);
    MerlTableInfo info{path, channel, 0};
    for (double v : t) info.unmeasured += v < 0.0;
    info.mirror_symmetric = table_mirror_symmetric(t);
    s.tables.push_back(std::move(t));
    s.info.push_back(info);
    s.table_file.push_back(file);
    return int(s.info.size() - 1);
}

MerlTableInfo merl_table_info(int index) {
    Store& s = store();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (index < 0 || size_t(index) >= s.info.size())
        throw Error("internal error: no MERL table " + std::to_string(index));
    return s.info[size_t(index)];
}

void merl_model_data(MerlModelData& out) {
    Store& s = store();
    std::lock_guard<std::mutex> lock(s.mutex);
    out.joined.clear();
    if (s.tables.size() == 1) {
        out.data = s.tables.front().data();
        out.size = s.tables.front().size();
        return;
    }
    out.joined.reserve(std::max<size_t>(1, s.tables.size() * BB_MERL_BINS));
    for (const auto& t : s.tables) out.joined.insert(out.joined.end(), t.begin(), t.end());
    if (out.joined.empty()) out.joined.push_back(0.0);
    out.data = out.joined.data();
    out.size = out.joined.size();
}

double merl_unmeasured_share(int index, int interp, double mu, int n) {
    const double* t = bb_merl_host_table(index);
    const double so = std::sqrt(std::max(0.0, 1 - mu * mu));
    const bb_vec3 wo = bb_v3(so, 0.0, mu);
    // A linear lookup of a mirror-symmetric table (bb_merl_mirror_symmetric) reads the same nodes
    // at a pair's mirror image (y -> -y), and the cells b and n - 1 - b in phi are mirror images:
    // half the cells, each counted twice (the nearest lookup's bins do not mirror onto bins).
    const bool mirror = interp == BB_MERL_LINEAR && n % 2 == 0 && merl_table_info(index).mirror_symmetric;
    const int nb = mirror ? n / 2 : n;
    long hits = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < nb; ++b) {
            const bb_vec3 wi = bb_cosine_hemisphere((a + 0.5) / n, (b + 0.5) / n);
            if (!(wi.z > 0.0 && wo.z > 0.0)) continue;
            const bb_vec3 x = bb_merl_coords(wo, wi);
            const double v = interp == BB_MERL_LINEAR ? bb_merl_linear(t, x) : bb_merl_nearest(t, x);
            hits += v < 0.0;
        }
    return double(mirror ? 2 * hits : hits) / (double(n) * n);
}

bool merl_unmeasured(const ModelConfig& model, const std::vector<double>& mus, MerlUnmeasured& out) {
    if (model.id != BB_MODEL_MERL) return false;
    const int index = int(model.params[BB_MERL_TABLE]);
    out.bins = merl_table_info(index).unmeasured;
    out.share.clear();
    for (double mu : mus)
        out.share.push_back(out.bins == 0 ? 0.0 : merl_unmeasured_share(index, int(model.params[BB_MERL_INTERP]), mu));
    return true;
}

std::string merl_unmeasured_line(const ModelConfig& model, const std::vector<double>& mus) {
    MerlUnmeasured u;
    if (!merl_unmeasured(model, mus, u)) return "";
    size_t worst = 0;
    for (size_t i = 1; i < u.share.size(); ++i)
        if (u.share[i] > u.share[worst]) worst = i;
    char line[256];
    std::snprintf(line, sizeof line, "# unmeasured: %zu of %d bins, read as 0", u.bins, BB_MERL_BINS);
    std::string text = line;
    if (!u.share.empty()) {
        std::snprintf(line, sizeof line, "; they take up to %.3g%% of the cosine-weighted hemisphere of wi (mu = %g)",
                      100.0 * u.share[worst], mus[worst]);
        text += line;
    }
    return text + "\n";
}

/// A merl spec's channel key: "-" for another model, "" where the spec names none.
static std::string merl_channel_key(const std::string& spec) {
    const Spec s = parse_spec(spec);
    if (s.name != "merl") return "-";
    for (const auto& kv : s.keys)
        if (kv.first == "channel") return kv.second;
    return "";
}

bool merl_rgb_spec(const std::string& spec) { return merl_channel_key(spec) == "rgb"; }

bool merl_per_colour(const std::string& spec) {
    const std::string c = merl_channel_key(spec);
    return c == "rgb" || c.empty();
}

std::string merl_channel_spec(const std::string& spec, const std::string& channel) {
    Spec s = parse_spec(spec);
    bool set = false;
    for (auto& kv : s.keys)
        if (kv.first == "channel") {
            kv.second = channel;
            set = true;
        }
    if (!set) s.keys.emplace_back("channel", channel);
    return spec_text(s);
}

std::string merl_spec_beside(const std::string& spec, const std::string& from) {
    const size_t slash = from.find_last_of('/');
    Spec s = parse_spec(spec);
    if (s.name != "merl" || slash == std::string::npos) return spec;
    for (auto& kv : s.keys)
        if (kv.first == "file" && kv.second[0] != '/' && kv.second != kBuiltinLambert)
            kv.second = from.substr(0, slash + 1) + kv.second;
    return spec_text(s);
}

}  // namespace brdfbake

const double* bb_merl_host_table(int index) {
    brdfbake::Store& s = brdfbake::store();
    std::lock_guard<std::mutex> lock(s.mutex);
    if (index < 0 || size_t(index) >= s.tables.size()) return nullptr;
    return s.tables[size_t(index)].data();
}

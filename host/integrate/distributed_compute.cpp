#include "integrate/distributed_compute.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <utility>

#include "engine/distributed.h"
#include "engine/hash.h"
#include "models/key_reader.h"

namespace brdfbake {
namespace {

// Packed numbers, bit for bit (the ranks of a job and a shard's reader run the same binary).
struct Packer {
    std::string s;
    template <typename T>
    void put(const T& v) {
        s.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
};

struct Reader {
    const std::string& s;
    size_t at = 0;
    template <typename T>
    T get() {
        if (at + sizeof(T) > s.size()) throw Error("a shard record or a rank's message is truncated");
        T v;
        std::memcpy(&v, s.data() + at, sizeof v);
        at += sizeof v;
        return v;
    }
};

void put_value(Packer& p, const AlbedoValue& v) {
    p.put(v.value);
    p.put(v.error);
    p.put(v.samples);
    p.put(std::int32_t(v.method));
}

AlbedoValue get_value(Reader& r) {
    AlbedoValue v;
    v.value = r.get<double>();
    v.error = r.get<double>();
    v.samples = r.get<std::uint64_t>();
    v.method = Method(r.get<std::int32_t>());
    return v;
}

// What one integration call reports besides its cells' values.
struct CallSummary {
    std::string method;
    unsigned vector_width = 1;
    std::uint64_t samples_per_cell = 0;
    double kernel_seconds = 0.0;
};

// The two kinds of integration call, seen alike: the values of a cell, the call's summary, the
// settings that key a shard's records.
std::vector<AlbedoValue> values_of(const AlbedoResult& r, size_t c) { return {r.values[c]}; }
std::vector<AlbedoValue> values_of(const DielectricResult& r, size_t c) { return {r.reflected[c], r.transmitted[c]}; }

void set_values(AlbedoResult& r, size_t c, const std::vector<AlbedoValue>& v) { r.values[c] = v.at(0); }
void set_values(DielectricResult& r, size_t c, const std::vector<AlbedoValue>& v) {
    r.reflected[c] = v.at(0);
    r.transmitted[c] = v.at(1);
}

void size_result(AlbedoResult& r, size_t n) { r.values.assign(n, AlbedoValue{}); }
void size_result(DielectricResult& r, size_t n) {
    r.reflected.assign(n, AlbedoValue{});
    r.transmitted.assign(n, AlbedoValue{});
}

CallSummary summary_of(const AlbedoResult& r) { return {r.method, r.vector_width, r.samples_per_cell, r.kernel_seconds}; }
CallSummary summary_of(const DielectricResult& r) {
    return {r.method, r.vector_width, r.samples_per_cell, r.kernel_seconds};
}

// The summary onto a whole result; an albedo's total is the sum of its cells' samples (every
// cell of a sampled call spends samples_per_cell, a quadrature cell its own count).
void apply_summary(AlbedoResult& r, const CallSummary& s) {
    r.method = s.method;
    r.vector_width = s.vector_width;
    r.samples_per_cell = s.samples_per_cell;
    r.kernel_seconds = s.kernel_seconds;
    r.total_samples = 0;
    for (const AlbedoValue& v : r.values) r.total_samples += v.samples;
}
void apply_summary(DielectricResult& r, const CallSummary& s) {
    r.method = s.method;
    r.vector_width = s.vector_width;
    r.samples_per_cell = s.samples_per_cell;
    r.kernel_seconds = s.kernel_seconds;
}

// The settings of a request: every field but the cells, hashed in order after a tag. Each
// settings_key names the request's fields by a structured binding, which stops compiling when a
// field is added to the struct: a new field cannot be left out of the key by oversight.
template <typename... Fields>
std::uint64_t hash_settings(char tag, const Fields&... fields) {
    Fnv1a h;
    h.add(tag);
    (h.add(fields), ...);
    return h.h;
}

std::uint64_t settings_key(const AlbedoRequest& q) {
    const auto& [model, fresnel, cells, method, samples, replicas, precision, seed, vector_width] = q;
    (void)cells;  // the records, not the settings
    return hash_settings('A', model, fresnel.kind, fresnel.params, int(method), samples, replicas, int(precision), seed,
                         vector_width);
}

std::uint64_t settings_key(const DielectricRequest& q) {
    const auto& [cells, shadowing, transmission_shadowing, method, samples, replicas, precision, seed, vector_width] =
        q;
    (void)cells;
    return hash_settings('D', int(method), int(shadowing), int(transmission_shadowing), samples, replicas,
                         int(precision), seed, vector_width);
}

std::string record_key(std::uint64_t settings, std::uint64_t cell) {
    Fnv1a h;
    h.add(settings);
    h.add(cell);
    static const char* digits = "0123456789abcdef";
    std::string key(16, '0');
    for (int i = 0; i < 16; ++i) key[size_t(i)] = digits[(h.h >> (60 - 4 * i)) & 15];
    return key;
}

template <typename Request>
Request subset(const Request& request, const std::vector<size_t>& cells) {
    Request r = request;
    r.cells.clear();
    for (size_t c : cells) r.cells.push_back(request.cells[c]);
    return r;
}

// Calls made while computing a part are this process's own.
thread_local bool g_inside = false;
struct Inside {
    Inside() { g_inside = true; }
    ~Inside() { g_inside = false; }
};

enum class Mode { Ranks, Recording, Replaying };
Mode g_mode = Mode::Ranks;
int g_shard_index = 0, g_shard_count = 1;
ShardRecords g_records;
std::map<std::string, std::uint32_t> g_text_index;

// The cells rank `rank` of `ranks` computes.
std::vector<size_t> rank_cells(size_t n, int rank, int ranks) {
    std::vector<size_t> cells;
    if (rank_split() == RankSplit::Block) {
        const size_t first = n * size_t(rank) / size_t(ranks), last = n * size_t(rank + 1) / size_t(ranks);
        for (size_t c = first; c < last; ++c) cells.push_back(c);
    } else {
        for (size_t c = size_t(rank); c < n; c += size_t(ranks)) cells.push_back(c);
    }
    return cells;
}

// MPI: every rank computes its cells and sends them to all. A rank whose part failed reports it
// in this step (every rank throws JobFailure); a non-finite sample is no failure of the job but
// the result of the call: every rank throws the NonFiniteError that one process would have
// thrown (the first such cell).
template <typename Request, typename Result, typename Compute>
Result share_among_ranks(const Request& request, Compute compute) {
    const size_t n = request.cells.size();
    const int ranks = dist::size();
    const std::vector<size_t> mine = rank_cells(n, dist::rank(), ranks);
    Packer p;
    try {
        if (!mine.empty()) {
            Inside inside;
            const Result part = compute(subset(request, mine));
            const CallSummary s = summary_of(part);
            p.put('V');
            p.put(std::uint32_t(s.method.size()));
            p.s += s.method;
            p.put(s.vector_width);
            p.put(s.samples_per_cell);
            p.put(s.kernel_seconds);
            for (size_t j = 0; j < mine.size(); ++j)
                for (const AlbedoValue& v : values_of(part, j)) put_value(p, v);
        } else {
            p.put('-');
        }
    } catch (const NonFiniteError& e) {
        p.s.clear();
        p.put('N');
        p.put(std::uint64_t(mine.at(e.cell)));
        p.put(std::uint64_t(e.count));
        p.s += e.what();
    } catch (...) {
        const Error job = dist::report_failure(dist::describe_failure(std::current_exception()));
        throw dist::JobFailure(job.what(), job.exit_code());
    }
    const std::vector<std::string> all = dist::exchange(p.s);

    // The first non-finite cell, as one process would report it.
    std::uint64_t bad_cell = ~std::uint64_t(0), bad_count = 0;
    std::string bad_message;
    for (const std::string& payload : all) {
        if (payload.empty() || payload[0] != 'N') continue;
        Reader r{payload, 1};
        const std::uint64_t cell = r.get<std::uint64_t>(), count = r.get<std::uint64_t>();
        if (cell < bad_cell) {
            bad_cell = cell;
            bad_count = count;
            bad_message = payload.substr(r.at);
        }
    }
    if (bad_count > 0) throw NonFiniteError(bad_message, size_t(bad_cell), bad_count);

    Result result;
    size_result(result, n);
    CallSummary total;
    bool first = true;
    for (int q = 0; q < ranks; ++q) {
        const std::string& payload = all[size_t(q)];
        if (payload.empty() || payload[0] != 'V') continue;
        Reader r{payload, 1};
        const std::uint32_t length = r.get<std::uint32_t>();
        CallSummary s;
        s.method = payload.substr(r.at, length);
        r.at += length;
        s.vector_width = r.get<unsigned>();
        s.samples_per_cell = r.get<std::uint64_t>();
        s.kernel_seconds = r.get<double>();
        if (first) {
            total.method = s.method;
            total.vector_width = s.vector_width;
            first = false;
        }
        total.samples_per_cell = std::max(total.samples_per_cell, s.samples_per_cell);
        total.kernel_seconds += s.kernel_seconds;
        const size_t per_cell = values_of(result, 0).size();
        for (size_t c : rank_cells(n, q, ranks)) {
            std::vector<AlbedoValue> values;
            for (size_t k = 0; k < per_cell; ++k) values.push_back(get_value(r));
            set_values(result, c, values);
        }
    }
    apply_summary(result, total);
    return result;
}

// A shard: its own cells computed and recorded, the others placeholders.
template <typename Request, typename Result, typename Compute>
Result record_shard(const Request& request, Compute compute) {
    const size_t n = request.cells.size();
    std::vector<size_t> mine;
    // The identity mixed first (MurmurHash3's 64-bit finaliser, Appleby 2011): FNV-1a's low bits
    // are the XOR of its bytes' low bits, which put all 64 cells of an 8x8 table in one of 2 shards.
    auto owner = [](std::uint64_t h) {
        h = (h ^ (h >> 33)) * 0xff51afd7ed558ccdull;
        h = (h ^ (h >> 33)) * 0xc4ceb9fe1a85ec53ull;
        return (h ^ (h >> 33)) % std::uint64_t(g_shard_count);
    };
    for (size_t c = 0; c < n; ++c)
        if (owner(cell_identity(request.cells[c])) == std::uint64_t(g_shard_index)) mine.push_back(c);
    Result result;
    size_result(result, n);
    if (mine.empty()) return result;
    Result part;
    {
        Inside inside;
        part = compute(subset(request, mine));
    }
    const CallSummary s = summary_of(part);
    auto [text, added] = g_text_index.emplace(s.method, std::uint32_t(g_records.texts.size()));
    if (added) g_records.texts.push_back(s.method);
    const std::uint64_t settings = settings_key(request);
    for (size_t j = 0; j < mine.size(); ++j) {
        const std::vector<AlbedoValue> values = values_of(part, j);
        Packer p;
        p.put(s.samples_per_cell);
        p.put(s.vector_width);
        p.put(text->second);
        p.put(std::uint8_t(values.size()));
        for (const AlbedoValue& v : values) put_value(p, v);
        g_records.cells[record_key(settings, cell_identity(request.cells[mine[j]]))] = p.s;
        set_values(result, mine[j], values);
    }
    apply_summary(result, s);
    return result;
}

// A merge: every cell from the shards' records.
template <typename Request, typename Result>
Result replay(const Request& request) {
    const std::uint64_t settings = settings_key(request);
    Result result;
    size_result(result, request.cells.size());
    CallSummary total;
    for (size_t c = 0; c < request.cells.size(); ++c) {
        const auto it = g_records.cells.find(record_key(settings, cell_identity(request.cells[c])));
        if (it == g_records.cells.end())
            throw Error("the part files hold no result for a cell this table needs (mu = " +
                        format_number(request.cells[c].mu) +
                        "); were they written by this version of brdfbake with this command?");
        Reader r{it->second};
        const std::uint64_t samples = r.get<std::uint64_t>();
        const unsigned width = r.get<unsigned>();
        const std::uint32_t text = r.get<std::uint32_t>();
        const std::uint8_t count = r.get<std::uint8_t>();
        if (text >= g_records.texts.size()) throw Error("a part file refers to a method text it does not hold");
        std::vector<AlbedoValue> values;
        for (std::uint8_t k = 0; k < count; ++k) values.push_back(get_value(r));
        set_values(result, c, values);
        if (c == 0) {
            total.method = g_records.texts[text];
            total.vector_width = width;
        }
        total.samples_per_cell = std::max(total.samples_per_cell, samples);
    }
    apply_summary(result, total);
    return result;
}

template <typename Request, typename Result, typename Compute>
std::optional<Result> share(const Request& request, Compute compute) {
    if (g_inside || request.cells.empty()) return std::nullopt;
    switch (g_mode) {
    case Mode::Replaying:
        return replay<Request, Result>(request);
    case Mode::Recording:
        return record_shard<Request, Result>(request, compute);
    case Mode::Ranks:
        if (!dist::active()) return std::nullopt;
        return share_among_ranks<Request, Result>(request, compute);
    }
    return std::nullopt;
}

}  // namespace

std::uint64_t cell_identity(const AlbedoCell& cell) {
    Fnv1a h;
    h.add(cell.mu);
    h.add(cell.phi);
    h.add(cell.params);
    return h.h;
}

std::uint64_t cell_identity(const DielectricCell& cell) {
    Fnv1a h;
    h.add(cell.mu);
    h.add(cell.alpha);
    h.add(cell.eta);
    return h.h;
}

RankSplit rank_split() {
    static const RankSplit split = [] {
        const char* s = std::getenv("BRDFBAKE_MPI_SPLIT");
        return s && std::string(s) == "block" ? RankSplit::Block : RankSplit::Cyclic;
    }();
    return split;
}

std::optional<AlbedoResult> shared_albedo(Engine& engine, const AlbedoRequest& request) {
    return share<AlbedoRequest, AlbedoResult>(request, [&](const AlbedoRequest& r) { return compute_albedo(engine, r); });
}

std::optional<DielectricResult> shared_dielectric(Engine& engine, const DielectricRequest& request) {
    return share<DielectricRequest, DielectricResult>(
        request, [&](const DielectricRequest& r) { return compute_dielectric(engine, r); });
}

void begin_shard(int index, int count) {
    if (count < 1 || index < 0 || index >= count) throw Error("--shard K/N needs 0 <= K < N");
    g_mode = Mode::Recording;
    g_shard_index = index;
    g_shard_count = count;
    g_records = ShardRecords{};
    g_text_index.clear();
}

const ShardRecords& shard_records() { return g_records; }

void begin_replay(ShardRecords records) {
    g_mode = Mode::Replaying;
    g_records = std::move(records);
}

}  // namespace brdfbake

// SPDX-License-Identifier: BSD-3-Clause
#include "stickslip/checkpoint.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <system_error>
#include <unistd.h>

#include "stickslip/detail/atomic_file.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/version.hpp"

namespace stickslip {

namespace {

using json = nlohmann::ordered_json;

constexpr const char* kFormat = "stickslip-checkpoint";
constexpr int kFormatVersion = 1;

/// FNV-1a, 64 bits: a checksum against truncation and bit rot, not an attacker.
std::uint64_t fnv1a(const std::string& s) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : s) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    return h;
}

std::string hex64(std::uint64_t x) { return number_text::hex(x, 16); }

// The exact sums are mostly zero words: a run of k zero words is written
// "zK.", any other word as 16 hex digits.
std::string encode_words(const std::vector<std::uint64_t>& w) {
    std::string out;
    for (std::size_t i = 0; i < w.size();) {
        if (w[i] == 0) {
            std::size_t j = i;
            while (j < w.size() && w[j] == 0) ++j;
            out += 'z'; // (one append at a time: GCC 12 warns falsely on "z" + ... + ".")
            out += std::to_string(j - i);
            out += '.';
            i = j;
        } else {
            out += hex64(w[i++]);
        }
    }
    return out;
}

bool decode_words(const std::string& s, std::vector<std::uint64_t>& w) {
    w.clear();
    for (std::size_t i = 0; i < s.size();) {
        if (s[i] == 'z') {
            const std::size_t dot = s.find('.', i);
            if (dot == std::string::npos || dot == i + 1 || dot - i > 12) return false;
            std::uint64_t k = 0;
            for (std::size_t c = i + 1; c < dot; ++c) {
                if (s[c] < '0' || s[c] > '9') return false;
                k = k * 10 + static_cast<std::uint64_t>(s[c] - '0');
            }
            if (k > (1u << 28)) return false;
            w.insert(w.end(), k, 0);
            i = dot + 1;
        } else {
            if (i + 16 > s.size()) return false;
            std::uint64_t x = 0;
            for (std::size_t c = i; c < i + 16; ++c) {
                const char ch = s[c];
                const int d = ch >= '0' && ch <= '9' ? ch - '0' : ch >= 'a' && ch <= 'f' ? ch - 'a' + 10 : -1;
                if (d < 0) return false;
                x = x << 4 | static_cast<std::uint64_t>(d);
            }
            w.push_back(x);
            i += 16;
        }
    }
    return true;
}

[[noreturn]] void refuse(const std::string& file, const std::string& why) {
    throw InvalidParameter("resume", "cannot resume from '" + file + "': " + why);
}

std::string cannot_write(const std::string& path, int err) {
    return "cannot write '" + path + "': " + std::strerror(err);
}

[[noreturn]] void refuse_path(const std::string& why) { throw InvalidParameter("checkpoint", why); }

/// The start of every checkpoint (json::dump(1) of an object whose first
/// member is the format), looked for before reading a whole file that may be
/// anything, a large data file included.
const std::string& format_marker() {
    static const std::string marker = std::string("\"format\": \"") + kFormat + "\"";
    return marker;
}

} // namespace

void validate(const CheckpointOptions& options) {
    if (!(options.every > 0) || !std::isfinite(options.every))
        throw InvalidParameter("checkpoint-every", "checkpoint-every must be a finite number of seconds > 0");
}

RunJournal::RunJournal(std::string command, std::vector<std::pair<std::string, std::string>> settings,
                       CheckpointOptions options, unsigned rank)
    : command_(std::move(command)), settings_(std::move(settings)), options_(std::move(options)), rank_(rank) {
    validate(options_);
    if (!options_.path.empty()) check_path();
    if (!options_.resume.empty()) read(options_.resume);
    last_write_ = std::chrono::steady_clock::now();
    if (!writes()) return;
    // At once, so that a path that cannot be written fails before any work.
    try {
        store();
    } catch (const std::system_error& e) {
        refuse_path(cannot_write(options_.path, e.code().value()));
    }
}

void RunJournal::check_path() {
    using Kind = detail::FileTarget::Kind;
    const std::string& p = options_.path;
    const detail::FileTarget t = detail::resolve_target(p);
    if (t.error) refuse_path(cannot_write(p, t.error));
    if (t.kind == Kind::directory) refuse_path("'" + p + "' is a directory");
    // A checkpoint is replaced whole at every write: renaming a file over a
    // device, a FIFO or a socket would destroy it (as root, /dev/null for
    // every program), and writing through one would keep nothing to resume.
    if (t.kind != Kind::regular && t.kind != Kind::missing)
        refuse_path("'" + p + "' is " + detail::describe(t.kind) + ", not a regular file; a checkpoint must be one");
    // Replacing a file one may not write would bypass its permissions.
    if (t.exists() && ::faccessat(AT_FDCWD, t.path.c_str(), W_OK, AT_EACCESS) != 0)
        refuse_path(cannot_write(p, errno));
    target_ = t.path; // a link stays a link: its target is what gets replaced
    if (!options_.resume.empty()) {
        const detail::FileTarget r = detail::resolve_target(options_.resume);
        if (!r.error && detail::same_file(t, r)) {
            // --checkpoint F --resume F with no F yet: the first run of a job
            // that is restarted with the same command line.
            if (!t.exists()) options_.resume.clear();
            return;
        }
    }
    if (!t.exists() || t.size == 0) return; // nothing in it to lose
    // Whatever is there would be overwritten at the first write: refused
    // unless it is a checkpoint of this very run, whose loss costs only time.
    std::ifstream in(t.path, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    const std::string keep = "; refusing to overwrite it: remove it or choose another path";
    if (head.find(format_marker()) == std::string::npos)
        refuse_path("'" + p + "' exists and is not a stickslip checkpoint" + keep);
    std::deque<Call> calls;
    const std::string why = load(t.path, calls);
    if (!why.empty()) refuse_path("'" + p + "' holds a checkpoint that is not this run's (" + why + ")" + keep);
    if (options_.resume.empty() && writes())
        warn("'" + p + "' holds a checkpoint of this same run, which now starts afresh and overwrites it (--resume " +
             p + " would continue it)");
}

void RunJournal::warn(const std::string& line) const {
    if (options_.warn) options_.warn(line);
    else std::fprintf(stderr, "stickslip: warning: checkpoint: %s\n", line.c_str());
}

RunJournal::Call& RunJournal::begin_call(std::uint64_t samples, std::uint64_t first_index, std::size_t words) {
    if (next_ < calls_.size()) {
        Call& c = calls_[next_];
        if (c.samples != samples || c.first_index != first_index || c.words.size() != words)
            refuse(options_.resume, "its run " + std::to_string(next_ + 1) + " was of " + std::to_string(c.samples) +
                                        " samples from index " + std::to_string(c.first_index) + ", this one is of " +
                                        std::to_string(samples) + " from " + std::to_string(first_index));
        ++next_;
        return c;
    }
    Call& c = calls_.emplace_back();
    c.samples = samples;
    c.first_index = first_index;
    c.words.assign(words, 0);
    ++next_;
    return c;
}

void RunJournal::updated() {
    if (!writes()) return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last_write_).count() >= options_.every) write();
}

void RunJournal::write() {
    if (!writes()) return;
    // A checkpoint is insurance, not the result: a write that fails (a full
    // disk, a folder gone) is said once, and the run goes on to its result.
    try {
        store();
        if (failing_) warn("'" + options_.path + "' written again");
        failing_ = false;
    } catch (const std::system_error& e) {
        if (!failing_)
            warn(cannot_write(options_.path, e.code().value()) +
                 "; the run goes on (its result is unaffected) without checkpoints until a write succeeds");
        failing_ = true;
    }
    last_write_ = std::chrono::steady_clock::now();
}

void RunJournal::store() { detail::write_file_atomically(target_, serialise()); }

std::string RunJournal::serialise() const {
    json j;
    j["format"] = kFormat;
    j["format_version"] = kFormatVersion;
    j["program"] = version_line();
    j["command"] = command_;
    json s = json::object();
    for (const auto& [k, v] : settings_) s[k] = v;
    j["settings"] = s;
    json calls = json::array();
    for (const Call& c : calls_) {
        json e;
        e["samples"] = c.samples;
        e["first_index"] = c.first_index;
        e["blocks_done"] = c.blocks_done;
        e["complete"] = c.complete;
        e["counts"] = c.counts;
        e["words"] = encode_words(c.words);
        calls.push_back(std::move(e));
    }
    j["calls"] = std::move(calls);
    j["checksum"] = hex64(fnv1a(j.dump()));
    return j.dump(1) + "\n";
}

void RunJournal::read(const std::string& file) {
    const std::string why = load(file, calls_);
    if (!why.empty()) refuse(file, why);
}

std::string RunJournal::load(const std::string& file, std::deque<Call>& calls) const {
    // A directory opens, and reads as an empty file.
    struct stat st {};
    if (::stat(file.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) return "it is a directory, not a checkpoint file";
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::strerror(errno);
    std::stringstream buf;
    buf << in.rdbuf();
    const std::string text = buf.str();
    if (text.find(format_marker()) == std::string::npos)
        return text.empty() ? "the file is empty" : "not a stickslip checkpoint";
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception&) {
        return "the file is truncated or corrupted (not valid JSON)";
    }
    try {
        const std::string sum = j.at("checksum").get<std::string>();
        j.erase("checksum");
        if (sum != hex64(fnv1a(j.dump()))) return "the file is corrupted (checksum mismatch)";
        if (j.at("format_version").get<int>() != kFormatVersion)
            return "checkpoint format version " + std::to_string(j.at("format_version").get<int>()) +
                   ", this program reads version " + std::to_string(kFormatVersion);
        const std::string prog = j.at("program").get<std::string>();
        if (prog != version_line()) return "written by " + prog + ", this is " + version_line();
        const std::string cmd = j.at("command").get<std::string>();
        if (cmd != command_) return "it is a checkpoint of `stickslip " + cmd + "`, not of `" + command_ + "`";
        const json& s = j.at("settings");
        for (const auto& [k, v] : settings_) {
            if (!s.contains(k)) return "it has no setting " + k;
            const std::string there = s.at(k).get<std::string>();
            if (there != v)
                return "written with " + k + " = " + (there.empty() ? "(unset)" : there) + ", this run has " + k +
                       " = " + (v.empty() ? "(unset)" : v);
        }
        if (s.size() != settings_.size()) return "it has settings this program does not know";
        for (const json& e : j.at("calls")) {
            Call c;
            c.samples = e.at("samples").get<std::uint64_t>();
            c.first_index = e.at("first_index").get<std::uint64_t>();
            c.blocks_done = e.at("blocks_done").get<std::uint64_t>();
            c.complete = e.at("complete").get<bool>();
            c.counts = e.at("counts").get<std::vector<std::uint64_t>>();
            if (!decode_words(e.at("words").get<std::string>(), c.words))
                return "the file is corrupted (bad sums)";
            calls.push_back(std::move(c));
        }
    } catch (const json::exception&) {
        return "the file is corrupted (a field is missing or of the wrong type)";
    }
    return "";
}

} // namespace stickslip

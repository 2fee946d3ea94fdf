// SPDX-License-Identifier: BSD-3-Clause
#include "config_file.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

#include <toml++/toml.h>

#include "stickslip/number_text.hpp"
#include "stickslip/setting.hpp"

namespace stickslip::cli {

namespace {

/// The key of line `number` (1-based) of `text` when it reads `key = ...`
/// (letters, digits, '-' and '_'), else "".
std::string key_on_line(const std::string& text, std::size_t number) {
    std::size_t begin = 0;
    for (std::size_t n = 1; n < number; ++n) {
        const std::size_t newline = text.find('\n', begin);
        if (newline == std::string::npos) return {};
        begin = newline + 1;
    }
    const std::string line = text.substr(begin, text.find('\n', begin) - begin);
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    std::size_t end = first;
    while (end < line.size() && (std::isalnum(static_cast<unsigned char>(line[end])) || line[end] == '-' || line[end] == '_'))
        ++end;
    const std::size_t equals = line.find_first_not_of(" \t", end);
    return end > first && equals != std::string::npos && line[equals] == '=' ? line.substr(first, end - first) : "";
}

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    throw InvalidParameter("config", "'" + path + "'" + why);
}

/// Line and column (from 1) of byte `at` of `text`.
std::string place(const std::string& text, std::size_t at) {
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k < at; ++k) {
        if (text[k] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

/// Refuses what is not a plain UTF-8 text file, with a message that names the
/// problem and its place and quotes none of the bytes (a BOM would otherwise
/// become part of the first key's name, and binary garbage the error line).
void check_text(const std::string& path, const std::string& text) {
    if (text.rfind("\xEF\xBB\xBF", 0) == 0)
        refuse(path, " starts with a byte-order mark (BOM); save it as UTF-8 without one");
    for (std::size_t k = 0; k < text.size();) {
        const auto c = static_cast<unsigned char>(text[k]);
        if (c == 0) refuse(path, " contains a NUL byte (" + place(text, k) + "): not a text settings file");
        if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
            refuse(path, " is not a text settings file: control byte 0x" + number_text::hex(c, 2) + " at " +
                             place(text, k));
        const std::size_t n = utf8_sequence_length(std::string_view(text).substr(k));
        if (n == 0) refuse(path, " is not a text settings file: invalid UTF-8 at " + place(text, k));
        k += n;
    }
}

/// A scalar as a flag's text. Numbers in shortest round-trip form, so that the
/// setting reads back exactly the double toml++ read.
std::string scalar_text(const toml::node& node, const std::string& path, const std::string& key) {
    if (const auto* s = node.as_string()) return s->get();
    if (const auto* i = node.as_integer()) return std::to_string(i->get());
    if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
    if (const auto* f = node.as_floating_point()) {
        const double x = f->get();
        if (std::isnan(x)) return "nan";
        if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
        char buffer[64];
        const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
        return std::string(buffer, end);
    }
    refuse(path, ": setting '" + printable_text(key) + "' (line " + std::to_string(node.source().begin.line) +
                     ") takes a number, a quoted text or a list of numbers, not a date or time");
}

} // namespace

std::vector<ConfigEntry> read_config_file(const std::string& path) {
    // A folder opens and reads as an empty file: refuse it rather than run
    // the defaults (found by tests/fuzz/).
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
        throw InvalidParameter("config", "cannot read '" + path + "': " + std::strerror(EISDIR));
    std::ifstream file(path, std::ios::binary);
    if (!file) throw InvalidParameter("config", "cannot read '" + path + "': " + std::strerror(errno));
    std::string text;
    char buffer[65536];
    while (file.read(buffer, sizeof buffer) || file.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(file.gcount()));
        if (text.size() > config_max_bytes)
            refuse(path, " is larger than 1 MiB: not a settings file (--print-config writes a few kB)");
    }
    check_text(path, text);

    toml::table table;
    try {
        table = toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        const std::string what(e.description());
        const std::string at = " (line " + std::to_string(e.source().begin.line) + ", column " +
                               std::to_string(e.source().begin.column) + ")";
        // TOML forbids a key twice; say it as the settings' own message.
        if (const auto redefine = what.find("cannot redefine existing "); redefine != std::string::npos) {
            const auto open = what.find('\'', redefine), close = what.rfind('\'');
            if (open != std::string::npos && close > open)
                refuse(path, ": setting '" + printable_text(what.substr(open + 1, close - open - 1)) +
                                 "' is given more than once; keep one line for it" + at);
        }
        // Name the setting whose value broke the line (`grid = fast`: "saw 'fas'").
        const std::string key = key_on_line(text, e.source().begin.line);
        const std::string setting = key.empty() ? "" : "the value of '" + key + "' (--" + key + "): ";
        const bool wide = what.find("not representable in 64 bits") != std::string::npos;
        refuse(path, " is not TOML: " + setting + printable_text(what) + at +
                         (wide ? "; a seed above 2^63 - 1 is written quoted (seed = \"12345678901234567890\")"
                               : "; write `key = value` lines, text quoted (drift = \"-v\"), lists bracketed "
                                 "(noise = [1, 2])"));
    }

    std::vector<ConfigEntry> entries;
    for (const auto& [key, node] : table) {
        const std::string name(key.str());
        const std::size_t line = node.source().begin.line;
        if (node.is_table() || node.is_array_of_tables())
            refuse(path, ": sections ([" + printable_text(name) + "], line " + std::to_string(line) +
                             ") are not read; write one `key = value` per line");
        std::string value;
        if (const auto* list = node.as_array()) {
            for (std::size_t k = 0; k < list->size(); ++k) {
                const toml::node& item = *list->get(k);
                if (item.is_array() || item.is_table())
                    refuse(path, ": setting '" + printable_text(name) + "' (line " + std::to_string(line) +
                                     ") holds a nested list or table; give a flat list (noise = [1, 2])");
                if (k) value += ',';
                value += scalar_text(item, path, name);
            }
        } else {
            value = scalar_text(node, path, name);
        }
        entries.push_back(ConfigEntry{name, std::move(value), line});
    }
    // toml++'s table is ordered by key; the file's order gives the first
    // error where the user reads first.
    std::stable_sort(entries.begin(), entries.end(),
                     [](const ConfigEntry& a, const ConfigEntry& b) { return a.line < b.line; });
    return entries;
}

} // namespace stickslip::cli

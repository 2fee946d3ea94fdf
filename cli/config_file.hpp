// SPDX-License-Identifier: BSD-3-Clause
// Reading a --config file: TOML, parsed by toml++ (a kept library: the
// hand-written reader it replaces took a '#' inside a quoted value for a
// comment, so --print-config then --config failed for a path with a '#').
// What it returns is the settings' text, exactly as a flag would give it, so
// that a value means the same on the command line and in a file; which keys
// exist and what their values may be is the caller's (SettingFlags) business.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace stickslip::cli {

/// One `key = value` line of a config file.
struct ConfigEntry {
    std::string key;   ///< as written (the caller maps '_' to '-')
    std::string value; ///< as a flag's text: a list as "a,b,c", a number in shortest round-trip form
    std::size_t line;  ///< from 1, for messages
};

/// Largest config file read (a settings file is a few kB; a larger one, such
/// as /dev/zero, is refused before it fills memory).
inline constexpr std::size_t config_max_bytes = 1u << 20;

/// The entries of the TOML file at `path`, in the file's order. Throws
/// InvalidParameter("config", ...) naming the file, and the line and column or
/// the key, when the file cannot be read, is larger than config_max_bytes, is
/// not plain UTF-8 text (a byte-order mark, a NUL or a control byte), is not
/// TOML, has a section ([name], a dotted key, an inline table), a date or a
/// nested list, or gives a key twice.
std::vector<ConfigEntry> read_config_file(const std::string& path);

} // namespace stickslip::cli

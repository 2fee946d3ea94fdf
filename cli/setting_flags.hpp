// SPDX-License-Identifier: BSD-3-Clause
// The settings of a request (setting.hpp) as command-line flags and as the
// keys of a config file: one flag per setting, generated from the request's
// visit_settings(), with the default that --help shows taken from a
// default-constructed request. --config FILE reads any of them from a TOML file
// (config_file.hpp), and flags on the command line override it; --print-config writes
// the effective settings in that form, so that --config of its output
// reproduces the run exactly.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "stickslip/setting.hpp"

namespace stickslip::cli {

/// The value of a boolean flag: false when absent, else the last value given
/// (`--flag` alone is true; `--flag=false`, `=0`, `=no`, `=off` are false).
/// Every boolean flag goes through here and parse_setting(bool), so they all
/// take the same forms and refuse the same others (InvalidParameter `name`).
bool flag_value(const CLI::Option& option, const char* name);

/// The flags of one subcommand's request. add_to() registers them; after
/// parsing, apply() fills the request: its defaults, then the config file,
/// then the command line.
class SettingFlags {
public:
    /// Registers one flag per setting of `request`, plus --config and
    /// --print-config. `request` must outlive this object: the flags write into it.
    template <class Request>
    void add_to(CLI::App* app, Request& request) {
        std::vector<std::string> defaults;
        Request fresh;
        visit_settings(fresh, [&](auto&& field, const SettingInfo&) { defaults.push_back(format_setting(field)); });
        std::size_t k = 0;
        visit_settings(request, [&](auto&& field, const SettingInfo& info) {
            add_setting<decltype(field)>(info, std::forward<decltype(field)>(field), defaults[k++]);
        });
        current_ = [&request] { return setting_entries(request); };
        register_options(app);
    }

    /// Fills the request from the config file (if any), then the command line.
    /// InvalidParameter names the setting, or "config" for the file itself.
    void apply();

    /// True when --print-config was given (with no value, or a true one);
    /// known after apply().
    bool print_config() const { return print_config_; }
    /// The --config file's path as given ("" without one); known after apply().
    const std::string& config_path() const { return config_path_; }
    /// The effective settings as a config file: one `key = value  # [unit] help`
    /// line per setting, under a comment naming the command.
    std::string config_text(const std::string& command) const;

private:
    struct Setting {
        SettingInfo info;
        const char* form;
        SettingKind kind;
        std::string default_text; ///< the default, as --help shows it
        std::function<void(const std::string&)> parse; ///< text -> the request's field
        std::string text;         ///< the command line's value
        CLI::Option* option = nullptr;
    };

    template <class Field, class Arg>
    void add_setting(const SettingInfo& info, Arg&& field, std::string default_text) {
        using Plain = std::decay_t<Field>;
        std::function<void(const std::string&)> parse;
        if constexpr (std::is_lvalue_reference_v<Field>) // a member: write through a reference to it
            parse = [&field, info](const std::string& text) { parse_setting(info, text, field); };
        else // a wrapper (OptionalNumber, ...) that holds references: keep a copy
            parse = [wrapper = Plain(field), info](const std::string& text) { parse_setting(info, text, wrapper); };
        settings_.push_back(Setting{info, info.form ? info.form : setting_form(field), setting_kind<Plain>(),
                                    std::move(default_text),
                                    std::move(parse), {}, nullptr});
    }

    void register_options(CLI::App* app);
    Setting* find(const std::string& key);

    std::vector<Setting> settings_;
    std::function<std::vector<SettingEntry>()> current_; ///< the request's settings with their values, in order
    CLI::Option* config_ = nullptr;
    CLI::Option* print_config_option_ = nullptr;
    std::string config_path_;
    bool print_config_ = false;
};

} // namespace stickslip::cli

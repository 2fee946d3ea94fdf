// SPDX-License-Identifier: BSD-3-Clause
#include "setting_flags.hpp"

#include "config_file.hpp"

#include <filesystem>
#include <set>

#include "stickslip/number_text.hpp"
#include "stickslip/version.hpp"

namespace stickslip::cli {

bool flag_value(const CLI::Option& option, const char* name) {
    if (option.count() == 0) return false;
    // CLI11 keeps what followed '=' as given ("true" for the flag alone); read
    // it as any other boolean setting rather than let any value turn it on.
    const std::vector<std::string>& given = option.results();
    bool value = true;
    parse_setting(SettingInfo{name, "", ""}, given.empty() ? std::string("true") : given.back(), value);
    return value;
}

void SettingFlags::register_options(CLI::App* app) {
    for (Setting& s : settings_) {
        std::string help = s.info.help;
        if (*s.info.unit) help += " [" + std::string(s.info.unit) + "]";
        const std::string flag = "--" + std::string(s.info.name);
        if (s.kind == SettingKind::Flag) {
            s.option = app->add_flag(flag)->description(help + " (also --" + std::string(s.info.name) +
                                                         "=true|false)");
        } else {
            s.option = app->add_option(flag, s.text, help)->type_name(s.form);
            if (!s.default_text.empty()) s.option->default_str(s.default_text);
        }
    }
    config_ = app->add_option("--config", config_path_,
                              "read the settings from FILE (TOML: one `key = value` per line, keys spelled as the "
                              "flags without '--', text quoted, lists bracketed; what --print-config writes); "
                              "flags given here override it")
                  ->type_name("FILE");
    print_config_option_ =
        app->add_flag("--print-config")
            ->description("print the effective settings of this command (every setting, defaults included, with "
                          "units) in --config form, to stdout or --output, after checking them as a run would, and "
                          "exit");
}

SettingFlags::Setting* SettingFlags::find(const std::string& key) {
    std::string name = key;
    for (char& c : name)
        if (c == '_') c = '-';
    for (Setting& s : settings_)
        if (name == s.info.name) return &s;
    return nullptr;
}

void SettingFlags::apply() {
    if (config_ && config_->count() > 0) {
        const std::string& path = config_path_;
        std::set<std::string> seen;
        for (const ConfigEntry& item : read_config_file(path)) {
            Setting* s = find(item.key);
            if (!s)
                throw InvalidParameter("config", "'" + path + "': unknown setting '" + printable_text(item.key) +
                                                     "' (line " + std::to_string(item.line) + ")");
            // max-steps and max_steps: one setting given twice, which one
            // the user meant is unknowable (TOML itself forbids a key twice).
            if (!seen.insert(s->info.name).second)
                throw InvalidParameter("config", "'" + path + "': setting '" + std::string(s->info.name) +
                                                     "' is given more than once; keep one line for it (line " +
                                                     std::to_string(item.line) + ")");
            if (s->option->count() > 0) continue; // the command line overrides the file
            std::string value = item.value;
            // A relative table path in a config file names a file beside the
            // config, not in the working directory (one config, two laws).
            if (std::string(s->info.name) == "drift-table" && !value.empty() && value.front() != '/') {
                const auto folder = std::filesystem::path(path).parent_path();
                if (!folder.empty()) value = (folder / value).string();
            }
            try {
                s->parse(value);
            } catch (const InvalidParameter& e) {
                throw InvalidParameter(e.parameter(), std::string(e.what()) + " (in '" + path + "', line " +
                                                           std::to_string(item.line) + ")");
            }
        }
    }
    // A drift law replaces the affine one: --relaxation or --bias beside it
    // would be ignored, so the command line may not give both (a config file
    // from --print-config holds both, and its relaxation and bias are unused).
    auto given = [&](const char* name) {
        const Setting* s = find(name);
        return s && s->option->count() > 0;
    };
    for (const char* law : {"drift", "drift-table"})
        for (const char* affine : {"relaxation", "bias"})
            if (given(law) && given(affine))
                throw InvalidParameter(affine, std::string("cannot be combined with --") + law +
                                                   ", which gives the whole drift law b(v): put the drag and the "
                                                   "constant force into it (e.g. --drift \"0.342 - v/0.067\")");
    if (given("drift") && given("drift-table"))
        throw InvalidParameter("drift-table", "cannot be combined with --drift: give the law once");
    // An explicit empty law ran the default Fig. 2 law (a script with an
    // unset variable got the wrong model, issue 50); a config file's
    // `drift = ""` (--print-config writes it) still means none.
    for (const char* law : {"drift", "drift-table"})
        if (given(law) && find(law)->text.empty())
            throw InvalidParameter(law, std::string("--") + law + " is empty; leave it out for the affine law of "
                                                                "--relaxation and --bias");
    for (Setting& s : settings_) {
        if (s.option->count() == 0) continue;
        if (s.kind == SettingKind::Flag) s.parse(flag_value(*s.option, s.info.name) ? "true" : "false");
        else s.parse(s.text);
    }
    print_config_ = flag_value(*print_config_option_, "print-config");
}

std::string SettingFlags::config_text(const std::string& command) const {
    std::string out = "# stickslip " + command + ": the effective settings (stickslip " + version() +
                      "). Run them again with\n#   stickslip " + command +
                      " --config FILE\n# and override any of them with flags.\n";
    for (SettingEntry entry : current_()) {
        // A relative table path in the file would be read beside the file:
        // write where it is, wherever the file is kept.
        if (std::string(entry.info.name) == "drift-table" && !entry.text.empty() && entry.text.front() != '/')
            entry.text = std::filesystem::absolute(entry.text).lexically_normal().string();
        out += config_line(entry) + "\n";
    }
    return out;
}

} // namespace stickslip::cli

// SPDX-License-Identifier: BSD-3-Clause
#include "setting_flags.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sys/stat.h>

#include "stickslip/version.hpp"

namespace stickslip::cli {

void SettingFlags::register_options(CLI::App* app) {
    for (Setting& s : settings_) {
        std::string help = s.info.help;
        if (*s.info.unit) help += " [" + std::string(s.info.unit) + "]";
        const std::string flag = "--" + std::string(s.info.name);
        if (s.kind == Kind::Flag) {
            s.option = app->add_flag(flag)->description(help);
        } else {
            s.option = app->add_option(flag, s.text, help)->type_name(s.form);
            if (!s.default_text.empty()) s.option->default_str(s.default_text);
        }
    }
    config_ = app->add_option("--config", config_path_,
                              "read the settings from FILE (TOML: one `key = value` per line, keys spelled as the "
                              "flags without '--'; what --print-config writes); flags given here override it")
                  ->type_name("FILE");
    app->add_flag("--print-config", print_config_,
                  "print the effective settings of this command (every setting, defaults included, with units) in "
                  "--config form, and exit");
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
        std::ifstream in(path);
        if (!in) throw InvalidParameter("config", "cannot read '" + path + "': " + std::strerror(errno));
        // A folder opens, and reads as an empty file: refuse it rather than
        // run the defaults (found by tests/fuzz/).
        struct stat st {};
        if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
            throw InvalidParameter("config", "cannot read '" + path + "': " + std::strerror(EISDIR));
        std::vector<CLI::ConfigItem> items;
        try {
            items = CLI::ConfigTOML().from_config(in);
        } catch (const CLI::Error& e) {
            throw InvalidParameter("config", "'" + path + "' is not a settings file: " + e.what());
        }
        for (const CLI::ConfigItem& item : items) {
            if (item.name == "++" || item.name == "--") continue; // section markers
            if (!item.parents.empty())
                throw InvalidParameter("config", "'" + path + "': sections ([" + item.parents.front() +
                                                     "]) are not read; write one `key = value` per line");
            Setting* s = find(item.name);
            if (!s) throw InvalidParameter("config", "'" + path + "': unknown setting '" + item.name + "'");
            if (s->option->count() > 0) continue; // the command line overrides the file
            std::string text;
            for (std::size_t k = 0; k < item.inputs.size(); ++k) {
                if (k) text += ',';
                text += item.inputs[k];
            }
            try {
                s->parse(text);
            } catch (const InvalidParameter& e) {
                throw InvalidParameter(e.parameter(), std::string(e.what()) + " (in '" + path + "')");
            }
        }
    }
    for (Setting& s : settings_)
        if (s.option->count() > 0) s.parse(s.kind == Kind::Flag ? "true" : s.text);
}

std::string SettingFlags::config_text(const std::string& command) const {
    std::string out = "# stickslip " + command + ": the effective settings (stickslip " + version() +
                      "). Run them again with\n#   stickslip " + command +
                      " --config FILE\n# and override any of them with flags.\n";
    const std::vector<std::string> values = current_();
    for (std::size_t k = 0; k < settings_.size(); ++k) {
        const Setting& s = settings_[k];
        const std::string& v = values[k];
        std::string line = s.info.name + std::string(" = ");
        if (v.empty() && s.kind != Kind::Text) {
            line = "# " + line; // unset: its default depends on other settings
        } else if (s.kind == Kind::Text) {
            line += "\"" + v + "\"";
        } else if (s.kind == Kind::List && v.find(':') != std::string::npos) {
            line += "\"" + v + "\""; // lo:hi:n
        } else if (s.kind == Kind::List) {
            line += "[";
            for (char c : v) line += c == ',' ? std::string(", ") : std::string(1, c);
            line += "]";
        } else if (v == "auto") {
            line += "\"auto\""; // a NumberOrAuto left to the library
        } else {
            line += v;
        }
        if (line.size() < 32) line.resize(32, ' ');
        line += "  # ";
        if (*s.info.unit) line += "[" + std::string(s.info.unit) + "] ";
        out += line + s.info.help + "\n";
    }
    return out;
}

} // namespace stickslip::cli

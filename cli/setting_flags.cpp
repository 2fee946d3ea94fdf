// SPDX-License-Identifier: BSD-3-Clause
#include "setting_flags.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <sys/stat.h>

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

namespace {

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
/// problem and its place and quotes none of the bytes: CLI11's TOML reader
/// would otherwise pass a BOM into the first key's name, stop at a NUL, or echo
/// binary garbage into the error line.
void check_text(const std::string& path, const std::string& text) {
    if (text.rfind("\xEF\xBB\xBF", 0) == 0)
        throw InvalidParameter("config", "'" + path +
                                             "' starts with a byte-order mark (BOM); save it as UTF-8 without one");
    for (std::size_t k = 0; k < text.size();) {
        const auto c = static_cast<unsigned char>(text[k]);
        if (c == 0)
            throw InvalidParameter("config", "'" + path + "' contains a NUL byte (" + place(text, k) +
                                                 "): not a text settings file");
        if ((c < 0x20 && c != '\t' && c != '\n' && c != '\r') || c == 0x7f)
            throw InvalidParameter("config", "'" + path + "' is not a text settings file: control byte 0x" +
                                                 number_text::hex(c, 2) + " at " + place(text, k));
        const std::size_t n = utf8_sequence_length(std::string_view(text).substr(k));
        if (n == 0)
            throw InvalidParameter("config", "'" + path + "' is not a text settings file: invalid UTF-8 at " +
                                                 place(text, k));
        k += n;
    }
}

} // namespace

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
                              "flags without '--'; what --print-config writes); flags given here override it")
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
        std::ifstream file(path, std::ios::binary);
        if (!file) throw InvalidParameter("config", "cannot read '" + path + "': " + std::strerror(errno));
        // A folder opens, and reads as an empty file: refuse it rather than
        // run the defaults (found by tests/fuzz/).
        struct stat st {};
        if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
            throw InvalidParameter("config", "cannot read '" + path + "': " + std::strerror(EISDIR));
        const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
        check_text(path, text);
        std::istringstream in(text);
        std::vector<CLI::ConfigItem> items;
        try {
            items = CLI::ConfigTOML().from_config(in);
        } catch (const CLI::Error& e) {
            throw InvalidParameter("config", "'" + path + "' is not a settings file: " + printable_text(e.what()));
        }
        std::set<std::string> seen;
        for (const CLI::ConfigItem& item : items) {
            if (item.name == "++" || item.name == "--") continue; // section markers
            if (!item.parents.empty())
                throw InvalidParameter("config", "'" + path + "': sections ([" + printable_text(item.parents.front()) +
                                                     "]) are not read; write one `key = value` per line");
            Setting* s = find(item.name);
            if (!s)
                throw InvalidParameter("config", "'" + path + "': unknown setting '" + printable_text(item.name) + "'");
            // Two lines for one setting: which one the user meant is unknowable
            // (TOML itself forbids it).
            if (!seen.insert(s->info.name).second)
                throw InvalidParameter("config", "'" + path + "': setting '" + std::string(s->info.name) +
                                                     "' is given more than once; keep one line for it");
            if (s->option->count() > 0) continue; // the command line overrides the file
            std::string value;
            for (std::size_t k = 0; k < item.inputs.size(); ++k) {
                if (k) value += ',';
                value += item.inputs[k];
            }
            // A relative table path in a config file names a file beside the
            // config, not in the working directory (one config, two laws).
            if (std::string(s->info.name) == "drift-table" && !value.empty() && value.front() != '/') {
                const auto folder = std::filesystem::path(path).parent_path();
                if (!folder.empty()) value = (folder / value).string();
            }
            try {
                s->parse(value);
            } catch (const InvalidParameter& e) {
                throw InvalidParameter(e.parameter(), std::string(e.what()) + " (in '" + path + "')");
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
    for (const SettingEntry& entry : current_()) out += config_line(entry) + "\n";
    return out;
}

} // namespace stickslip::cli

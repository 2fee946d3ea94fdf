// SPDX-License-Identifier: BSD-3-Clause
#include "harness.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <set>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <unordered_set>

#include "commands.hpp"
#include "output.hpp"
#include "run.hpp"
#include "setting_flags.hpp"
#include "stickslip/bruteforce.hpp"
#include "stickslip/checkpoint.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/version.hpp"
#include "stickslip/white_noise.hpp"

namespace stickslip::fuzz {

namespace {

// ---- reporting ------------------------------------------------------------------------------

/// A duplicate of the real stderr, made before libFuzzer's -close_fd_mask
/// sends fd 2 to /dev/null.
int g_report_fd = 2;

std::string show(const std::vector<std::string>& args) {
    std::string s;
    for (const auto& a : args) {
        s += s.empty() ? "" : " ";
        s += "'" + a + "'";
    }
    return s;
}

[[noreturn]] void finding(const std::vector<std::string>& args, const std::string& what) {
    const std::string text = "\n==stickslip-fuzz== FINDING: " + what + "\n==stickslip-fuzz== arguments: " +
                             show(args) + "\n";
    if (::write(g_report_fd, text.data(), text.size()) < 0) {
    }
    std::abort();
}

// ---- the sandbox ------------------------------------------------------------------------------

struct Sandbox {
    std::string dir, config, roundtrip, output, checkpoint, resume, missing_file, missing_folder_file;
};

Sandbox& sandbox() {
    static Sandbox s;
    return s;
}

void remove_sandbox() {
    const Sandbox& s = sandbox();
    if (s.dir.empty()) return;
    for (const std::string& f : {s.config, s.roundtrip, s.output, s.checkpoint, s.resume}) ::unlink(f.c_str());
    ::rmdir(s.dir.c_str());
}

void make_sandbox() {
    const char* tmp = std::getenv("TMPDIR");
    std::string dir = std::string(tmp && *tmp ? tmp : "/tmp") + "/stickslip-fuzz-XXXXXX";
    std::vector<char> buf(dir.begin(), dir.end());
    buf.push_back('\0');
    if (!::mkdtemp(buf.data())) {
        std::fprintf(stderr, "stickslip-fuzz: cannot make a sandbox folder %s: %s\n", dir.c_str(), std::strerror(errno));
        std::exit(1);
    }
    Sandbox& s = sandbox();
    s.dir = buf.data();
    s.config = s.dir + "/config.toml";
    s.roundtrip = s.dir + "/roundtrip.toml";
    s.output = s.dir + "/out.txt";
    s.checkpoint = s.dir + "/run.ckpt";
    s.resume = s.dir + "/resume.ckpt";
    s.missing_file = s.dir + "/missing.toml";
    s.missing_folder_file = s.dir + "/missing/out.txt";
    std::atexit(remove_sandbox);
}

void write_file(const std::string& path, const std::string& text) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << text;
    if (!f) {
        std::fprintf(stderr, "stickslip-fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
}

// ---- capture of the real command's stdout and stderr ---------------------------------------------

struct Capture {
    bool on = false;
    int out = -1, err = -1, null = -1;
};
Capture g_capture;

void rewind(int fd) {
    if (::ftruncate(fd, 0) != 0 || ::lseek(fd, 0, SEEK_SET) != 0) std::abort();
}

std::string slurp(int fd) {
    std::string s;
    char buf[4096];
    off_t at = 0;
    for (;;) {
        const ssize_t n = ::pread(fd, buf, sizeof buf, at);
        if (n <= 0) break;
        s.append(buf, static_cast<std::size_t>(n));
        at += n;
    }
    return s;
}

// ---- the dry path: a replica of commands.cpp that stops before computing ---------------------

enum class Expect { parse_error, help, print_config, bad_input, io_error, would_compute };

const char* name(Expect e) {
    switch (e) {
    case Expect::parse_error: return "a parse error";
    case Expect::help: return "--help/--version";
    case Expect::print_config: return "--print-config";
    case Expect::bad_input: return "bad input";
    case Expect::io_error: return "an I/O error";
    case Expect::would_compute: return "a computation";
    }
    return "?";
}

struct DryOutcome {
    Expect expect = Expect::parse_error;
    std::string command;
    bool applied = false;    ///< apply() succeeded: config_text and valid are set
    std::string config_text; ///< what --print-config prints
    bool valid = false;      ///< validate(request) passed
    std::string validation;  ///< its message when not
    std::string output;      ///< --output: where --print-config writes
};

struct DryCommand {
    CLI::App* app;
    std::function<DryOutcome()> run;
};

/// commands.cpp's resumable(): runs through the block driver, with --checkpoint/--resume.
template <class Request>
constexpr bool resumable() {
    if constexpr (requires { Request::resumable; }) return Request::resumable;
    return false;
}

/// commands.cpp's CheckpointFlags and add_checkpoint_flags().
struct CheckpointFlags {
    CheckpointOptions options;
    std::string every;
};

void add_checkpoint_flags(CLI::App* app, CheckpointFlags& o) {
    app->add_option("--checkpoint", o.options.path, CheckpointOptions::path_help)->type_name("FILE");
    app->add_option("--checkpoint-every", o.every, CheckpointOptions::every_help);
    app->add_option("--resume", o.options.resume, CheckpointOptions::resume_help)->type_name("FILE");
}

/// commands.cpp's read_checkpoint_flags().
void read_checkpoint_flags(CheckpointFlags& o) {
    if (!o.every.empty())
        parse_setting(SettingInfo{"checkpoint-every", "s", CheckpointOptions::every_help}, o.every, o.options.every);
    validate(o.options);
}

/// One subcommand as commands.cpp's add_command() builds it (the same flags,
/// from the same request), run up to the computation: apply() and the other
/// flags, validate() (which --print-config and the computation call first),
/// --print-config, the output, and the checkpoint journal (which reads
/// --resume and writes a first --checkpoint).
template <class Request, class Result>
DryCommand add_dry(CLI::App& app, Result (*)(const Request&)) {
    struct State {
        Request request;
        cli::SettingFlags flags;
        cli::OutputFlags output;
        CheckpointFlags checkpoint;
    };
    auto state = std::make_shared<State>();
    const std::string command = Request::command;
    CLI::App* sub = app.add_subcommand(command, command);
    state->flags.add_to(sub, state->request);
    cli::add_output_flags(sub, state->output);
    if constexpr (resumable<Request>()) add_checkpoint_flags(sub, state->checkpoint);
    return {sub, [state, command] {
                DryOutcome o;
                o.command = command;
                o.output = state->output.output;
                try {
                    state->flags.apply();
                    cli::read_output_flags(state->output);
                    if constexpr (resumable<Request>()) read_checkpoint_flags(state->checkpoint);
                } catch (const InvalidParameter&) {
                    o.expect = Expect::bad_input;
                    return o;
                }
                o.applied = true;
                o.config_text = state->flags.config_text(command);
                try {
                    validate(state->request);
                    o.valid = true;
                } catch (const InvalidParameter& e) {
                    o.validation = e.parameter() + ": " + e.what();
                }
                if (state->flags.print_config()) {
                    o.expect = o.valid ? Expect::print_config : Expect::bad_input;
                    try {
                        cli::Output out(state->output); // checks --format and --output
                    } catch (const InvalidParameter&) {
                        o.expect = Expect::bad_input;
                    }
                    return o;
                }
                try {
                    if constexpr (resumable<Request>()) cli::refuse_shared_paths(state->output, state->checkpoint.options);
                    cli::Output out(state->output); // opens (and, leaving, removes) the temporary
                    if constexpr (resumable<Request>()) {
                        try {
                            CheckpointOptions quiet = state->checkpoint.options;
                            quiet.warn = [](const std::string&) {}; // the real run's stderr is the one checked
                            const std::unique_ptr<RunJournal> journal = make_journal(state->request, quiet);
                        } catch (const InvalidParameter&) {
                            throw; // an unwritable checkpoint path included: exit 2
                        } catch (const std::runtime_error&) {
                            o.expect = Expect::io_error;
                            return o;
                        }
                    }
                } catch (const InvalidParameter&) {
                    o.expect = Expect::bad_input;
                    return o;
                }
                o.expect = o.valid ? Expect::would_compute : Expect::bad_input;
                return o;
            }};
}

/// The main app's settings, as run_command() makes them.
void configure_main(CLI::App& app) {
    app.footer(cli::kConventions);
    app.require_subcommand(1);
    app.set_version_flag("--version", stickslip::version_line());
}

/// register_all(), dry: the subcommands in the same order with the same requests.
std::vector<DryCommand> register_dry(CLI::App& app) {
    return {
        add_dry(app, &compute_diffusivity),
        add_dry(app, &compute_bruteforce),
        add_dry(app, &compute_density),
        add_dry(app, &compute_moments),
        add_dry(app, &compute_correlation),
        add_dry(app, &compute_trajectory),
        add_dry(app, &compute_white_noise),
        add_dry(app, &compute_sweep),
    };
}

std::vector<char*> c_args(std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    return argv;
}

DryOutcome dry_run(std::vector<std::string> args) {
    CLI::App app{"stickslip (fuzz replica)"};
    configure_main(app);
    const auto commands = register_dry(app);
    std::vector<char*> argv = c_args(args);
    DryOutcome o;
    try {
        app.parse(static_cast<int>(args.size()), argv.data());
    } catch (const CLI::CallForHelp&) {
        o.expect = Expect::help;
        return o;
    } catch (const CLI::CallForAllHelp&) {
        o.expect = Expect::help;
        return o;
    } catch (const CLI::CallForVersion&) {
        o.expect = Expect::help;
        return o;
    } catch (const CLI::ParseError&) {
        o.expect = Expect::parse_error;
        return o;
    }
    for (const auto& c : commands)
        if (c.app->parsed()) return c.run();
    std::abort(); // require_subcommand(1): unreachable
}

// ---- the real path ----------------------------------------------------------------------------

struct RealOutcome {
    int code = -1;
    std::string out, err;
};

RealOutcome real_run(std::vector<std::string> args) {
    std::vector<char*> argv = c_args(args);
    if (g_capture.on) {
        std::fflush(nullptr);
        rewind(g_capture.out);
        rewind(g_capture.err);
        ::dup2(g_capture.out, STDOUT_FILENO);
        ::dup2(g_capture.err, STDERR_FILENO);
    }
    RealOutcome r;
    r.code = cli::run_command(static_cast<int>(args.size()), argv.data());
    std::cout.flush();
    std::cerr.flush();
    std::fflush(nullptr);
    std::cout.clear();
    if (g_capture.on) {
        r.out = slurp(g_capture.out);
        r.err = slurp(g_capture.err);
        ::dup2(g_capture.null, STDOUT_FILENO);
        ::dup2(g_capture.null, STDERR_FILENO);
    }
    return r;
}

/// Exactly one line, "stickslip: error: ...\n".
bool one_error_line(const std::string& err) {
    const std::string prefix = "stickslip: error: ";
    return err.size() > prefix.size() && err.compare(0, prefix.size(), prefix) == 0 && err.back() == '\n' &&
           std::count(err.begin(), err.end(), '\n') == 1;
}

std::string quote_block(const std::string& s) { return s.empty() ? "(nothing)" : "\n" + s; }

void check_real(const std::vector<std::string>& args, const DryOutcome& dry) {
    const RealOutcome r = real_run(args);
    const std::string got = "exit " + std::to_string(r.code) + ", stdout: " + quote_block(r.out) +
                            "\nstderr: " + quote_block(r.err);
    switch (dry.expect) {
    case Expect::parse_error:
    case Expect::bad_input:
        if (r.code != cli::kExitBadInput) finding(args, std::string("expected exit 2 for ") + name(dry.expect) + ", got " + got);
        if (g_capture.on && (!r.out.empty() || !one_error_line(r.err)))
            finding(args, "bad input must print nothing on stdout and one 'stickslip: error:' line on stderr; got " +
                              got);
        return;
    case Expect::io_error:
        if (r.code != 1 || (g_capture.on && (!r.out.empty() || !one_error_line(r.err))))
            finding(args, "an I/O error must exit 1 with one 'stickslip: error:' line on stderr; got " + got);
        return;
    case Expect::help:
        if (r.code != 0 || (g_capture.on && (r.out.empty() || !r.err.empty())))
            finding(args, "--help/--version: expected exit 0 and text on stdout only, got " + got);
        return;
    case Expect::print_config: {
        // Written where --output says: stdout, a descriptor, or elsewhere.
        const std::string& o = dry.output;
        const bool to_out = o.empty() || o == "/dev/stdout" || o == "/dev/fd/1";
        const bool to_err = o == "/dev/stderr" || o == "/dev/fd/2";
        if (r.code != 0 || (g_capture.on && (r.out != (to_out ? dry.config_text : std::string()) ||
                                             r.err != (to_err ? dry.config_text : std::string()))))
            finding(args, "--print-config: expected exit 0 and the dry path's text" + quote_block(dry.config_text) +
                              "\nwritten to " + (o.empty() ? std::string("stdout") : o) + ", got " + got);
        return;
    }
    case Expect::would_compute: return;
    }
}

/// --print-config's text, read back with --config, prints the same text and
/// makes an equally valid request.
void check_round_trip(const std::vector<std::string>& args, const DryOutcome& dry) {
    if (!dry.applied) return;
    // Most inputs print one of a few texts: check each text once (a bounded
    // memory of those seen; more executions per second for the rest).
    static std::unordered_set<std::size_t> seen;
    if (seen.size() > (1u << 16)) seen.clear();
    if (!seen.insert(std::hash<std::string>{}(dry.command + '\n' + dry.config_text)).second) return;
    write_file(sandbox().roundtrip, dry.config_text);
    const DryOutcome back = dry_run({"stickslip", dry.command, "--config", sandbox().roundtrip, "--print-config"});
    // --print-config refuses settings that do not validate, from a file as from flags.
    const Expect want = back.valid ? Expect::print_config : Expect::bad_input;
    if (back.expect != want)
        finding(args, std::string("--print-config's text, read back with --config, gives ") + name(back.expect) +
                          " instead of " + name(want) + ":" + quote_block(dry.config_text));
    if (back.config_text != dry.config_text)
        finding(args, "--print-config's text, read back with --config, prints another text:" +
                          quote_block(dry.config_text) + "\nthen:" + quote_block(back.config_text));
    if (back.valid != dry.valid || back.validation != dry.validation)
        finding(args, "the request read back from --print-config's text validates differently: '" + dry.validation +
                          "' then '" + back.validation + "'");
}

// ---- flags and dictionary ----------------------------------------------------------------------

using FlagSets = std::vector<std::pair<std::string, std::set<std::string>>>;

std::set<std::string> option_names(const CLI::App* app) {
    std::set<std::string> names;
    for (const CLI::Option* opt : app->get_options()) names.insert(opt->get_name());
    return names;
}

/// The subcommands and their flags (first entry: the main app's, named "").
template <class Register>
FlagSets flag_sets(Register reg) {
    CLI::App app{"flags"};
    configure_main(app);
    const auto commands = reg(app);
    FlagSets sets{{"", option_names(&app)}};
    for (const auto& c : commands) sets.emplace_back(c.app->get_name(), option_names(c.app));
    return sets;
}

void check_replica() {
    const FlagSets real = flag_sets([](CLI::App& a) { return cli::register_all(a); });
    const FlagSets dry = flag_sets([](CLI::App& a) { return register_dry(a); });
    if (real != dry) {
        std::fprintf(stderr, "stickslip-fuzz: the dry replica in tests/fuzz/harness.cpp no longer matches "
                             "register_all() in cli/commands.cpp (subcommands or flags differ); update it\n");
        std::exit(1);
    }
}

void check_dictionary(const char* path) {
    std::ifstream in(path);
    if (!in) {
        std::fprintf(stderr, "stickslip-fuzz: cannot read the dictionary %s\n", path);
        std::exit(1);
    }
    std::set<std::string> words;
    std::string line;
    while (std::getline(in, line)) {
        const auto a = line.find('"'), b = line.rfind('"');
        if (line.empty() || line[0] == '#' || a == std::string::npos || b <= a) continue;
        words.insert(line.substr(a + 1, b - a - 1));
    }
    int missing = 0;
    for (const auto& [sub, flags] : flag_sets([](CLI::App& a) { return cli::register_all(a); })) {
        if (!sub.empty() && !words.count(sub)) {
            std::fprintf(stderr, "stickslip-fuzz: %s lacks the subcommand \"%s\"\n", path, sub.c_str());
            ++missing;
        }
        for (const auto& f : flags)
            if (!words.count(f)) {
                std::fprintf(stderr, "stickslip-fuzz: %s lacks the flag \"%s\" (of %s)\n", path, f.c_str(),
                             sub.empty() ? "stickslip" : sub.c_str());
                ++missing;
            }
    }
    std::fprintf(stderr, "stickslip-fuzz: %s: %zu words, %d flags or subcommands missing\n", path, words.size(),
                 missing);
    std::exit(missing == 0 ? 0 : 1);
}

/// The flags whose values are file names, and what they become (neutralise()).
enum class PathFlag { config, output, checkpoint, resume };

std::string path_value(const std::string& v, PathFlag flag) {
    const Sandbox& s = sandbox();
    const bool folder = !v.empty() && v.back() == '/';
    switch (flag) {
    case PathFlag::config:
        return folder ? s.dir : v.compare(0, 7, "missing") == 0 ? s.missing_file : s.config;
    case PathFlag::resume:
        return folder                                 ? s.dir
               : v.compare(0, 7, "missing") == 0      ? s.missing_file
               : v.compare(0, 10, "checkpoint") == 0 ? s.checkpoint
                                                      : s.resume;
    case PathFlag::output:
        if (v.empty()) return v;
        for (const char* dev : {"/dev/null", "/dev/stdout", "/dev/stderr", "/dev/fd/1", "/dev/fd/2"})
            if (v == dev) return v;
        [[fallthrough]];
    case PathFlag::checkpoint:
        return folder ? s.dir : v.find("missing") != std::string::npos ? s.missing_folder_file
                        : flag == PathFlag::output                   ? s.output
                                                                      : s.checkpoint;
    }
    return s.config;
}

/// CLI11 takes the next argument as an option's value unless it looks like an option.
bool looks_like_option(const std::string& a) {
    return a.size() > 1 && a[0] == '-' && (a[1] == '-' || std::isalpha(static_cast<unsigned char>(a[1])));
}

} // namespace

// ---- the interface ------------------------------------------------------------------------------

const std::string& config_path() { return sandbox().config; }

void write_config(const std::string& text) { write_file(sandbox().config, text); }

void write_resume(const std::string& text) { write_file(sandbox().resume, text); }

std::vector<std::string> neutralise(std::vector<std::string> args) {
    static const std::pair<const char*, PathFlag> flags[] = {{"--config", PathFlag::config},
                                                             {"--output", PathFlag::output},
                                                             {"--checkpoint", PathFlag::checkpoint},
                                                             {"--resume", PathFlag::resume}};
    for (std::size_t i = 1; i < args.size(); ++i) {
        std::string& a = args[i];
        for (const auto& [name, kind] : flags) {
            const std::string flag = name;
            if (a == flag && i + 1 < args.size() && !looks_like_option(args[i + 1])) {
                args[i + 1] = path_value(args[i + 1], kind);
                ++i;
                break;
            }
            if (a.compare(0, flag.size() + 1, flag + "=") == 0) {
                a = flag + "=" + path_value(a.substr(flag.size() + 1), kind);
                break;
            }
        }
    }
    return args;
}

const std::vector<std::string>& subcommands() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const auto& [sub, flags] : flag_sets([](CLI::App& a) { return cli::register_all(a); }))
            if (!sub.empty()) v.push_back(sub);
        return v;
    }();
    return names;
}

const std::string& resume_path() { return sandbox().resume; }

const std::vector<std::string>& resumable_subcommands() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> v;
        for (const auto& [sub, flags] : flag_sets([](CLI::App& a) { return cli::register_all(a); }))
            if (!sub.empty() && flags.count("--resume")) v.push_back(sub);
        return v;
    }();
    return names;
}

void check(const std::vector<std::string>& args) {
    ::unlink(sandbox().checkpoint.c_str()); // what a --checkpoint wrote: never left for the next input
    DryOutcome dry;
    try {
        dry = dry_run(args);
    } catch (const std::exception& e) {
        finding(args, std::string("an exception that is not InvalidParameter (exit 1, not 2): ") + e.what());
    }
    // A folder is not a settings file: reading one as an empty file would
    // run the defaults without a word.
    for (std::size_t i = 1; i < args.size(); ++i)
        if (dry.applied && (args[i] == "--config=" + sandbox().dir ||
                            (args[i] == "--config" && i + 1 < args.size() && args[i + 1] == sandbox().dir)))
            finding(args, "--config read a folder as an empty settings file instead of refusing it");
    if (dry.expect != Expect::would_compute) {
        ::unlink(sandbox().checkpoint.c_str()); // the dry path's first checkpoint: the real one starts afresh too
        check_real(args, dry);
    }
    try {
        check_round_trip(args, dry);
    } catch (const std::exception& e) {
        finding(args, std::string("reading --print-config's text back threw: ") + e.what());
    }
}

void initialize(int* argc, char*** argv) {
    make_sandbox();
    check_replica();
    if (const char* dict = std::getenv("STICKSLIP_FUZZ_CHECK_DICT")) check_dictionary(dict);

    // -close_fd_mask=3 unless the command line chooses: libFuzzer then keeps
    // its own output (and the sanitizers' reports) on a duplicate of stderr and
    // points fds 1 and 2 at /dev/null, where we can swap the capture in.
    std::string mask;
    for (int i = 1; i < *argc; ++i)
        if (std::strncmp((*argv)[i], "-close_fd_mask=", 15) == 0) mask = (*argv)[i] + 15;
    if (mask.empty()) {
        static std::vector<char*> extended;
        static char flag[] = "-close_fd_mask=3";
        extended.assign(*argv, *argv + *argc);
        extended.push_back(flag);
        extended.push_back(nullptr);
        *argv = extended.data();
        *argc += 1;
        mask = "3";
    }
    g_report_fd = ::dup(STDERR_FILENO);
    if (g_report_fd < 0) g_report_fd = STDERR_FILENO;
    if (mask == "3") {
        g_capture.out = ::memfd_create("stickslip-stdout", MFD_CLOEXEC);
        g_capture.err = ::memfd_create("stickslip-stderr", MFD_CLOEXEC);
        g_capture.null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
        g_capture.on = g_capture.out >= 0 && g_capture.err >= 0 && g_capture.null >= 0;
    }
}

} // namespace stickslip::fuzz

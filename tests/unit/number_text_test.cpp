// SPDX-License-Identifier: BSD-3-Clause
// number_text.hpp: numbers read and written whatever the locale, with
// printf's formats reproduced exactly (the golden outputs depend on it), and
// the settings, messages and reports that use it unmoved by a comma-decimal
// LC_NUMERIC or a global C++ locale that groups digits.
#include <gtest/gtest.h>

#include <clocale>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <locale>
#include <random>
#include <string>
#include <unistd.h>

#include "stickslip/diffusivity.hpp"
#include "stickslip/number_text.hpp"
#include "stickslip/report.hpp"
#include "stickslip/setting.hpp"
#include "stickslip/white_noise.hpp"

namespace {

using namespace stickslip;
namespace nt = stickslip::number_text;

std::string printf_text(const char* format, int precision, double x) {
    char buf[512];
    std::snprintf(buf, sizeof buf, format, precision, x);
    return buf;
}

/// Doubles of every kind: random bit patterns (subnormals, huge, tiny),
/// short decimals, integers, halfway cases and the specials.
std::vector<double> sample_doubles() {
    std::vector<double> xs = {0.0, -0.0, 1.0, -1.0, 0.5, 0.1, 0.125, 2.5, 1e-4, 9.9999995, 0.00095, 123456789.0,
                              1e16, 1e21, 1e22, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308,
                              std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::quiet_NaN()};
    std::mt19937_64 rng(12345);
    for (int k = 0; k < 20000; ++k) {
        std::uint64_t bits = rng();
        double x = 0;
        std::memcpy(&x, &bits, sizeof x);
        if (!std::isnan(x)) xs.push_back(x);
        xs.push_back(std::ldexp(static_cast<double>(rng() % 1000000), -static_cast<int>(rng() % 40)));
        xs.push_back(static_cast<double>(rng() % 100000) / 1000.0 + 0.0005); // near rounding ties at 3 decimals
    }
    return xs;
}

// --- writing: exactly printf in the C locale ------------------------------------------------

TEST(NumberText, GeneralScientificFixedEqualPrintf) {
    for (const double x : sample_doubles()) {
        for (int p = 0; p <= 17; ++p) {
            ASSERT_EQ(nt::general(x, p), printf_text("%.*g", p, x)) << "p = " << p;
            ASSERT_EQ(nt::scientific(x, p), printf_text("%.*e", p, x)) << "p = " << p;
            if (std::fabs(x) < 1e100 || !std::isfinite(x)) {
                ASSERT_EQ(nt::fixed(x, p), printf_text("%.*f", p, x));
            }
        }
    }
    EXPECT_EQ(nt::general(0.1), "0.1");
    EXPECT_EQ(nt::general(2.5e8), "2.5e+08");
    EXPECT_EQ(nt::general(-std::numeric_limits<double>::infinity()), "-inf");
    EXPECT_EQ(nt::fixed(1e300, 20).size(), 322u); // longer than any fixed buffer would be
    EXPECT_EQ(nt::general(1.0 / 3, -1), "0.333333"); // printf: a negative precision is 6
}

TEST(NumberText, LongDoubleGeneralEqualsPrintf) {
    std::mt19937_64 rng(7);
    for (int k = 0; k < 20000; ++k) {
        const long double x = static_cast<long double>(static_cast<double>(rng() % 1000000) / 7.0) /
                              static_cast<long double>(1 + rng() % 1000);
        char buf[128];
        std::snprintf(buf, sizeof buf, "%.6Lg", x);
        ASSERT_EQ(nt::general(x, 6), buf);
    }
}

TEST(NumberText, HexAndPad) {
    EXPECT_EQ(nt::hex(0, 16), "0000000000000000");
    EXPECT_EQ(nt::hex(0xcbf29ce484222325ull, 16), "cbf29ce484222325");
    EXPECT_EQ(nt::hex(0x1b, 2), "1b");
    EXPECT_EQ(nt::hex(0x1b), "1b");
    EXPECT_EQ(nt::pad("ab", 5), "   ab");
    EXPECT_EQ(nt::pad("ab", -5), "ab   ");
    EXPECT_EQ(nt::pad("abcdef", 3), "abcdef"); // never cut, as printf
    EXPECT_EQ(nt::pad("", 0), "");
}

// --- reading --------------------------------------------------------------------------------

TEST(NumberText, ReadsDecimalNumbers) {
    EXPECT_EQ(nt::read_double("0.9"), 0.9);
    EXPECT_EQ(nt::read_double("+1"), 1.0);
    EXPECT_EQ(nt::read_double("-2.5e-3"), -2.5e-3);
    EXPECT_EQ(nt::read_double(".5"), 0.5);
    EXPECT_EQ(nt::read_double("1."), 1.0);
    EXPECT_EQ(nt::read_double("1E5"), 1e5);
    EXPECT_EQ(nt::read_double("1e+5"), 1e5);
    EXPECT_EQ(nt::read_double("inf"), std::numeric_limits<double>::infinity());
    EXPECT_EQ(nt::read_double("-Infinity"), -std::numeric_limits<double>::infinity());
    EXPECT_EQ(nt::read_double("5e-324"), std::numeric_limits<double>::denorm_min());
    ASSERT_TRUE(nt::read_double("NaN"));
    EXPECT_TRUE(std::isnan(*nt::read_double("NaN")));
    // Underflow is the nearest double, as strtod gives it; overflow is refused.
    EXPECT_EQ(nt::read_double("1e-400"), 0.0);
    ASSERT_TRUE(nt::read_double("-1e-400"));
    EXPECT_TRUE(std::signbit(*nt::read_double("-1e-400")));
    EXPECT_EQ(nt::read_double("0.000001e-320"), 0.0);
    EXPECT_EQ(nt::read_double("0e999999999999"), 0.0);
    EXPECT_FALSE(nt::read_double("1e400"));
    EXPECT_FALSE(nt::read_double("-1e400"));
    EXPECT_FALSE(nt::read_double("1000000e303"));
    for (const char* bad : {"", " 1", "1 ", "0x10", "0x1p3", "1,5", "1e", "+-1", "++1", "--1", "-", "+", ".", "e5",
                            "1.2.3", "1e5x", "\xef\xbb\xbf" "1", "1\n"})
        EXPECT_FALSE(nt::read_double(bad)) << "'" << bad << "'";
}

TEST(NumberText, ReadsBackWhatItWrites) {
    for (const double x : sample_doubles()) {
        if (std::isnan(x)) continue;
        const auto back = nt::read_double(nt::general(x, 17));
        ASSERT_TRUE(back) << nt::general(x, 17);
        ASSERT_EQ(*back, x) << nt::general(x, 17);
    }
}

TEST(NumberText, ReadsUnsignedDigitsOnly) {
    EXPECT_EQ(nt::read_unsigned("0"), 0u);
    EXPECT_EQ(nt::read_unsigned("010"), 10u);
    EXPECT_EQ(nt::read_unsigned("18446744073709551615"), std::numeric_limits<std::uint64_t>::max());
    for (const char* bad : {"18446744073709551616", "-1", "+1", "", " 1", "1e3", "0x10", "1.0"})
        EXPECT_FALSE(nt::read_unsigned(bad)) << "'" << bad << "'";
}

// --- under other locales -----------------------------------------------------------------------

/// Switches LC_NUMERIC to a comma-decimal locale for the test's lifetime, and
/// back to "C" after. A system without one installed gets one made by
/// localedef in a temporary directory (LOCPATH), if it has the sources.
class CommaLocale {
public:
    CommaLocale() {
        for (const char* name : {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8", "de_DE", "fr_FR",
                                 "nl_NL.UTF-8", "it_IT.UTF-8", "ru_RU.UTF-8"})
            if (take(name)) return;
        if (::access("/usr/share/i18n/locales/de_DE", R_OK) != 0) return;
        char dir[] = "/tmp/stickslip_locale_XXXXXX";
        if (!::mkdtemp(dir)) return;
        dir_ = dir;
        const std::string command = "localedef -i de_DE -f UTF-8 '" + dir_ + "/de_DE.UTF-8' >/dev/null 2>&1";
        (void)std::system(command.c_str()); // warnings give a non-zero status; the result is tested below
        ::setenv("LOCPATH", dir_.c_str(), 1);
        if (!take("de_DE.UTF-8")) take("de_DE.utf8");
    }
    ~CommaLocale() {
        std::setlocale(LC_NUMERIC, "C");
        if (!dir_.empty()) {
            ::unsetenv("LOCPATH");
            (void)std::system(("rm -rf '" + dir_ + "'").c_str());
        }
    }
    bool active() const { return !name_.empty(); }
    const std::string& name() const { return name_; }

private:
    bool take(const char* name) {
        if (!std::setlocale(LC_NUMERIC, name)) return false;
        if (std::string(std::localeconv()->decimal_point) != ",") {
            std::setlocale(LC_NUMERIC, "C");
            return false;
        }
        name_ = name;
        return true;
    }
    std::string name_, dir_;
};

/// A global C++ locale whose numbers have a decimal comma and group thousands.
struct GroupingComma : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
    char do_thousands_sep() const override { return '.'; }
    std::string do_grouping() const override { return "\3"; }
};

DiffusivityRequest small_run() {
    DiffusivityRequest req;
    req.engine.scheme = Scheme::Resolvent;
    req.engine.dt = 1e-3;
    req.engine.dt_auto = false;
    req.excursions = 256;
    req.control.threads = 2;
    return req;
}

WhiteNoiseRequest white_request() {
    WhiteNoiseRequest req;
    req.params.friction = 1;
    req.params.noise = 1;
    req.params.relaxation = std::numeric_limits<double>::infinity();
    req.params.bias = 0;
    req.v0 = 1;
    req.times = {0.05, 0.5, 2.5};
    return req;
}

std::string without_seconds(std::string table) {
    // The work line's wall time differs from run to run.
    const auto at = table.find(" s on ");
    if (at == std::string::npos) return table;
    const auto start = table.rfind(", ", at);
    return table.erase(start, at - start);
}

TEST(NumberText, CommaDecimalCLocaleChangesNothing) {
    // Python and other hosts may set LC_NUMERIC from the environment: strtod
    // then refused "0.9" and snprintf wrote "0,5" into CSV files.
    const std::string c_csv = to_csv(compute_white_noise(white_request()));
    const std::string c_table = to_table(compute_white_noise(white_request()));
    const DiffusivityResult c_run = compute_diffusivity(small_run());
    const CommaLocale comma;
    if (!comma.active()) GTEST_SKIP() << "no comma-decimal locale is installed and localedef could not make one";
    char probe[32];
    std::snprintf(probe, sizeof probe, "%g", 0.5);
    ASSERT_STREQ(probe, "0,5") << "the locale " << comma.name() << " is not in effect";

    EXPECT_EQ(nt::read_double("0.9"), 0.9);
    EXPECT_EQ(nt::general(0.5), "0.5");
    EXPECT_EQ(format_setting(0.067), "0.067");
    double level = 0;
    parse_setting(SettingInfo{"level", "", ""}, "0.9", level);
    EXPECT_EQ(level, 0.9);
    std::vector<double> times;
    parse_setting(SettingInfo{"times", "s", ""}, "0.1:1:3", NumberList{times});
    EXPECT_EQ(times.size(), 3u);
    EXPECT_EQ(to_csv(compute_white_noise(white_request())), c_csv);
    EXPECT_EQ(to_table(compute_white_noise(white_request())), c_table);
    const DiffusivityResult run = compute_diffusivity(small_run());
    EXPECT_EQ(to_csv(run), to_csv(c_run));
    EXPECT_EQ(without_seconds(to_table(run)), without_seconds(to_table(c_run)));
    try {
        parse_setting(SettingInfo{"dt", "s", ""}, "1e400", level);
        ADD_FAILURE() << "1e400 was read";
    } catch (const InvalidParameter& e) {
        EXPECT_EQ(std::string(e.what()), "dt must be a number, got '1e400'");
    }
}

TEST(NumberText, GlobalCxxLocaleChangesNothing) {
    const DiffusivityResult run = compute_diffusivity(small_run());
    const std::string table = without_seconds(to_table(run)), csv = to_csv(run);
    const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new GroupingComma));
    const std::string grouped_table = without_seconds(to_table(run)), grouped_csv = to_csv(run);
    std::locale::global(previous);
    EXPECT_EQ(grouped_table, table);
    EXPECT_EQ(grouped_csv, csv);
    EXPECT_NE(table.find("256 excursions"), std::string::npos) << table;
}

TEST(NumberText, MessagesQuoteNoRawBytes) {
    EXPECT_EQ(printable_text("plain text, 0.5"), "plain text, 0.5");
    EXPECT_EQ(printable_text("a\x1b[31mb"), "a\\x1b[31mb");
    EXPECT_EQ(printable_text(std::string("a\0b", 3)), "a\\x00b");
    EXPECT_EQ(printable_text("r\xC3\xA9sum\xC3\xA9"), "r\xC3\xA9sum\xC3\xA9"); // UTF-8 stays
    EXPECT_EQ(printable_text("r\xE9sum\xE9"), "r\\xe9sum\\xe9");                // Latin-1 does not
    EXPECT_EQ(printable_text("\xEF\xBB\xBF" "x"), "\xEF\xBB\xBF" "x");          // a BOM is valid UTF-8
    EXPECT_EQ(printable_text("\xED\xA0\x80"), "\\xed\\xa0\\x80");               // a surrogate is not
    EXPECT_EQ(printable_text("\xC0\xAF"), "\\xc0\\xaf");                        // nor an overlong form
    double x = 0;
    try {
        parse_setting(SettingInfo{"dt", "s", ""}, "1\x07", x);
        ADD_FAILURE();
    } catch (const InvalidParameter& e) {
        EXPECT_EQ(std::string(e.what()), "dt must be a number, got '1\\x07'");
    }
}

} // namespace

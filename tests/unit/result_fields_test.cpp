// SPDX-License-Identifier: BSD-3-Clause
// A result's fields declared once (result_fields.hpp): the JSON block is
// written from the declaration alone, so a struct's new field reaches the
// report with no writer to edit. A test-only struct shows each FieldForm; the
// real ones are checked against the golden outputs, the schema
// (python/tools/make_schema.py --check) and the stubs.
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "report/fields_csv.hpp"
#include "report/fields_json.hpp"
#include "stickslip/diffusivity.hpp"
#include "stickslip/drift_law_quadrature.hpp"
#include "stickslip/kolmogorov.hpp"
#include "stickslip/observables.hpp"
#include "stickslip/report.hpp"
#include "stickslip/result_fields.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {
namespace {

struct Demo {
    double varied = std::numeric_limits<double>::quiet_NaN();
    double time = 2.5;
    std::uint64_t count = 7;
    bool done = true;
    std::string name = "demo";
    Estimate mean{1.0, 0.1, 0.8, 1.2, 0.95};
    Estimate rate{3.0, 0.3, 2.4, 3.6, 0.95};
    double seconds = 9.0;
    double limit = std::numeric_limits<double>::infinity();
    Estimate inner{4.0, 0.4, 3.2, 4.8, 0.95};

    template <class Visit> static constexpr void fields(Visit&& visit) {
        visit(&Demo::varied, FieldInfo{"varied", "", "set or not", FieldForm::WhenSet});
        visit(&Demo::time, FieldInfo{"time", "s", "a number"});
        visit(&Demo::count, FieldInfo{"count", "", "an integer"});
        visit(&Demo::done, FieldInfo{"done", "", "a flag"});
        visit(&Demo::name, FieldInfo{"name", "", "a text"});
        visit(&Demo::mean, FieldInfo{"mean", "m/s", "with its interval"});
        visit(&Demo::rate, FieldInfo{"rate", "1/s", "without", FieldForm::NoInterval});
        visit(&Demo::seconds, FieldInfo{"seconds", "s", "elsewhere", FieldForm::NotInBlock});
        visit(&Demo::limit, FieldInfo{"limit", "", "infinite"});
        visit(&Demo::inner, FieldInfo{"nested.inner", "m", "one level down"});
    }
};
static_assert(DeclaredFields<Demo>);
static_assert(DeclaredFields<SweepExponent> && DeclaredFields<SweepWhiteLimit> && DeclaredFields<ControlVariateReport>);
static_assert(!DeclaredFields<DiffusivityResult>);

TEST(ResultFields, TheJsonBlockFollowsTheDeclaration) {
    Demo d;
    const detail::ordered_json j = detail::fields_json(d);
    // In declaration order, less the unset and the reported-elsewhere fields.
    EXPECT_EQ(j.dump(),
              R"({"time":2.5,"count":7,"done":true,"name":"demo",)"
              R"("mean":{"value":1.0,"error":0.1,"ci":[0.8,1.2],"level":0.95,"kind":"sampled"},)"
              R"("rate":{"value":3.0,"error":0.3,"kind":"sampled"},"limit":"inf",)"
              R"("nested":{"inner":{"value":4.0,"error":0.4,"ci":[3.2,4.8],"level":0.95,"kind":"sampled"}}})");
    d.varied = 1.5;
    EXPECT_EQ(detail::fields_json(d).begin().key(), "varied");
    EXPECT_EQ(detail::fields_json(d)["varied"], 1.5);
}

TEST(ResultFields, TheCsvColumnsFollowTheDeclaration) {
    Demo d;
    d.name = "a, \"b\"";
    // An unset WhenSet field keeps its column (empty); a dotted name's dots are '_'.
    EXPECT_EQ(detail::fields_csv_header<Demo>(),
              "varied,time,count,done,name,mean,mean_error,mean_lo,mean_hi,rate,rate_error,limit,"
              "nested_inner,nested_inner_error,nested_inner_lo,nested_inner_hi");
    EXPECT_EQ(detail::fields_csv_row(d), ",2.5,7,true,\"a, \"\"b\"\"\",1,0.1,0.8,1.2,3,0.3,inf,4,0.4,3.2,4.8");
}

/// A result along an axis: the axis declared last, to show it leads the CSV anyway.
struct DemoSeries {
    std::vector<Estimate> level{{1.0, 0.1, 0.8, 1.2, 0.95}, {2.0, 0.2, 1.6, 2.4, 0.95}};
    Estimate total{3.0, 0.3, 2.4, 3.6, 0.95};
    std::vector<double> depth{0.5, 1.5};

    template <class Visit> static constexpr void fields(Visit&& visit) {
        visit(&DemoSeries::level, FieldInfo{"level", "m", "a series"});
        visit(&DemoSeries::total, FieldInfo{"total", "m", "a value beside it"});
        visit(&DemoSeries::depth, FieldInfo{"depth", "m", "the axis", FieldForm::Axis});
    }
};

TEST(ResultFields, ASeriesIsWrittenAlongItsAxis) {
    DemoSeries d;
    const detail::ordered_json j = detail::fields_json(d);
    EXPECT_EQ(j.dump(), R"({"level":[{"depth":0.5,"value":1.0,"error":0.1,"ci":[0.8,1.2],"kind":"sampled"},)"
                        R"({"depth":1.5,"value":2.0,"error":0.2,"ci":[1.6,2.4],"kind":"sampled"}],)"
                        R"("total":{"value":3.0,"error":0.3,"ci":[2.4,3.6],"level":0.95,"kind":"sampled"}})");
    // The CSV: a row per point, the axis first; values beside the series have no column.
    EXPECT_EQ(detail::series_csv_header<DemoSeries>(), "depth,level,level_error,level_lo,level_hi");
    EXPECT_EQ(detail::series_csv_rows(d), "0.5,1,0.1,0.8,1.2\n1.5,2,0.2,1.6,2.4\n");
    // A series longer than its axis is the writer's bug: refused, not read past the axis.
    d.level.push_back(d.total);
    EXPECT_THROW((void)detail::fields_json(d), std::logic_error);
    EXPECT_THROW((void)detail::series_csv_rows(d), std::logic_error);
}

TEST(ResultFields, AnEstimateIsWrittenAsItsKindSays) {
    Demo d;
    d.mean = solved_estimate(1.0, 0.1);
    d.rate = exact_estimate(3.0);
    const detail::ordered_json j = detail::fields_json(d);
    EXPECT_EQ(j["mean"].dump(), R"({"value":1.0,"error":0.1,"kind":"solved"})");
    EXPECT_EQ(j["rate"].dump(), R"({"value":3.0,"error":0.0,"kind":"exact"})");
}

TEST(ResultFields, AReferenceIsExactForTheAffineLawAndSolvedForADriftLaw) {
    SweepWhiteLimit w;
    w.white_diffusivity = 0.25;
    ModelParams affine;
    const detail::ordered_json j = detail::fields_json(w, detail::FieldJsonStyle{&affine});
    EXPECT_EQ(j["white_diffusivity"].dump(), R"({"value":0.25,"error":0.0,"kind":"exact"})");
    EXPECT_FALSE(j.contains("varied")); // NaN without --vary
    // Without the report's model a reference cannot say whose it is: the
    // writer's bug, refused (it was dereferenced).
    EXPECT_THROW((void)detail::fields_json(w), std::logic_error);
}

/// A struct that holds one of two declared blocks, and a field a report may leave out.
struct DemoPoint {
    double noise = 1.0;
    std::string rule = "stuck";
    Demo sampled;
    std::optional<Demo> solved;
    bool reached = true;

    template <class Visit> static constexpr void fields(Visit&& visit) {
        visit(&DemoPoint::noise, FieldInfo{"noise", "", "a number"});
        visit(&DemoPoint::rule, FieldInfo{"rule", "", "sampled only", FieldForm::Optional});
        visit(&DemoPoint::sampled, FieldInfo{"sampled", "", "a block, inlined", FieldForm::Optional});
        visit(&DemoPoint::solved, FieldInfo{"solved", "", "a block when present, inlined"});
        visit(&DemoPoint::reached, FieldInfo{"reached", "", "solved only", FieldForm::Optional});
    }
};

TEST(ResultFields, ABlockIsInlinedInItsPlaceAndAReportLeavesOutWhatItSays) {
    DemoPoint p;
    p.sampled.time = 1.0;
    // Sampled: the sampled block in its place, the solved absent, "reached" left out.
    const detail::ordered_json sampled = detail::fields_json(p, detail::FieldJsonStyle{nullptr, {"reached"}});
    std::vector<std::string> keys;
    for (const auto& item : sampled.items()) keys.push_back(item.key());
    ASSERT_GE(keys.size(), 4u);
    EXPECT_EQ(keys[0], "noise");
    EXPECT_EQ(keys[1], "rule");
    EXPECT_EQ(keys[2], "time"); // Demo's first written field
    EXPECT_EQ(keys.back(), "nested");
    EXPECT_EQ(sampled["time"], 1.0);
    EXPECT_FALSE(sampled.contains("reached"));
    // Solved: the solution's block, the sampled one and the rule left out.
    p.solved = Demo{};
    p.solved->time = 3.0;
    const detail::ordered_json solved = detail::fields_json(p, detail::FieldJsonStyle{nullptr, {"rule", "sampled"}});
    EXPECT_FALSE(solved.contains("rule"));
    EXPECT_EQ(solved["time"], 3.0);
    EXPECT_EQ(solved["reached"], true);
    EXPECT_EQ(solved.items().begin().key(), "noise");
}

TEST(ResultFields, AWorkBlockHasTheCountOfItsUnitAndWhatWasSet) {
    RunWork w;
    w.events = 12;
    w.seconds = 0.5;
    w.threads = 2;
    // The count under the report's unit alone; an empty threads_from, no
    // resumed samples and no corrector are not written.
    const detail::ordered_json events = detail::work_json(w, "events");
    std::vector<std::string> keys;
    for (const auto& item : events.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"events", "seconds", "threads"}));
    EXPECT_EQ(events["events"], 12u);
    // A sweep's work: no count, no threads; resumed samples when there were.
    RunWork sweep;
    sweep.seconds = 3.0;
    sweep.resumed_samples = 64;
    sweep.threads_from = "option";
    const detail::ordered_json j = detail::work_json(sweep, "");
    keys.clear();
    for (const auto& item : j.items()) keys.push_back(item.key());
    EXPECT_EQ(keys, (std::vector<std::string>{"seconds", "threads_from", "resumed_samples"}));
}

TEST(ResultFields, AHistogramsCsvHasARowPerBinAndPerMassOverItsVelocities) {
    VelocityHistogram h;
    h.edges = {-1.0, 0.0, 1.0};
    h.density = {Estimate{0.25, 0.05, 0.15, 0.35, 0.95}, Estimate{0.5, 0.1, 0.3, 0.7, 0.95}};
    h.below = Estimate{0.0, 0.0, 0.0, 0.0, 0.95};
    h.above = Estimate{0.125, 0.0, 0.125, 0.125, 0.95};
    h.stuck = Estimate{0.125, 0.01, 0.1, 0.15, 0.95};
    h.time = 2.0; // not an estimate: no row (a report puts it in the rows' head)
    EXPECT_EQ(detail::histogram_csv_header(), "kind,v_lo,v_hi,value,error,lo,hi");
    EXPECT_EQ(detail::histogram_csv_rows(h, {}, "2,"), "2,bins,-1,0,0.25,0.05,0.15,0.35\n"
                                                       "2,bins,0,1,0.5,0.1,0.3,0.7\n"
                                                       "2,below,-inf,-1,0,0,0,0\n"
                                                       "2,above,1,inf,0.125,0,0.125,0.125\n"
                                                       "2,stuck_probability,0,0,0.125,0.01,0.1,0.15\n");
    // A solver's: value and error alone; a left-out mass has no row.
    const detail::FieldCsvStyle solved{.omit = {"below", "above"}, .solved = true};
    EXPECT_EQ(detail::histogram_csv_header(solved), "kind,v_lo,v_hi,value,error");
    EXPECT_EQ(detail::histogram_csv_rows(h, solved),
              "bins,-1,0,0.25,0.05\nbins,0,1,0.5,0.1\nstuck_probability,0,0,0.125,0.01\n");
}

TEST(ResultFields, NamesAreUniqueAndDocumented) {
    auto check = [](auto tag) {
        using T = typename decltype(tag)::type;
        std::vector<std::string> names;
        T::fields([&](auto, const FieldInfo& f) {
            EXPECT_FALSE(std::string(f.help).empty()) << f.name;
            for (const auto& n : names) EXPECT_NE(n, f.name);
            names.push_back(f.name);
        });
        EXPECT_FALSE(names.empty());
    };
    check(std::type_identity<SweepExponent>{});
    check(std::type_identity<SweepWhiteLimit>{});
    check(std::type_identity<ControlVariateReport>{});
    check(std::type_identity<KolmogorovResult>{});
    check(std::type_identity<CorrelationResult>{});
    check(std::type_identity<MomentsResult>{});
    check(std::type_identity<DensityResult>{});
    check(std::type_identity<SweepPoint>{});
    check(std::type_identity<RunTotals>{});
    check(std::type_identity<KolmogorovGridSpan>{});
    check(std::type_identity<PrecisionOutcome>{});
    check(std::type_identity<WhiteNoiseReference>{});
    check(std::type_identity<VelocityHistogram>{});
    check(std::type_identity<ExcursionRecord>{});
    check(std::type_identity<NondimensionalValues>{});
    check(std::type_identity<RunWork>{});
}

} // namespace
} // namespace stickslip

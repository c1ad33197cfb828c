// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: the kernel contract suite's harness (contract_harness.h).
#include "python/contract_harness.h"

#include <algorithm>
#include <filesystem>

#include "support/stats.h"

namespace phasor::contract {

namespace {
Outcome *gCurrent = nullptr;
const Options *gOptions = nullptr;
int gCases = 0;
constexpr std::size_t MaxMessages = 5;  // per check and case; the rest are counted
}  // namespace

Outcome &Current() { return *gCurrent; }
const Options &CurrentOptions() { return *gOptions; }

long long Scaled(long long n) {
    if (gOptions->sampleScale >= 1) return n;
    return std::max<long long>(std::min<long long>(n, 1000), std::llround(double(n) * gOptions->sampleScale));
}

double Alpha(int testsPerCase) { return test::SidakAlpha(0.01, std::max(1, gCases * testsPerCase)); }

void Recorder::operator=(const Message &m) const {
    Outcome &o = Current();
    const std::string where = std::filesystem::path(file_).filename().string() + ":" + std::to_string(line_);
    const std::string text = m.Str();
    if (skip_) {
        o.skipped = true;
        o.messages.push_back(text.empty() ? "skipped" : "skipped: " + text);
        return;
    }
    o.failed = true;
    ++o.failures;
    if (o.messages.size() < MaxMessages) o.messages.push_back(where + ": " + what_ + (text.empty() ? "" : "\n    " + text));
}

std::vector<Check> &Checks() {
    static std::vector<Check> checks;
    return checks;
}

Report Run(const Options &o, int cases, const std::function<void(int)> &setParam,
           const std::function<std::string(int)> &caseName) {
    Report r;
    r.kernel = o.kernel;
    gOptions = &o;
    gCases = cases;
    for (int i = 0; i < cases; ++i) {
        r.cases.push_back(caseName(i));
        setParam(i);
        for (const Check &c : Checks()) {
            Outcome out;
            out.check = c.name;
            out.caseName = r.cases.back();
            gCurrent = &out;
            try {
                std::unique_ptr<TestBase> t = c.make();
                t->SetUp();
                if (!out.failed && !out.skipped) t->TestBody();
                t->TearDown();
            } catch (const std::exception &e) {
                if (o.fatal && o.fatal(e)) {
                    gCurrent = nullptr;
                    throw;
                }
                out.failed = true;
                ++out.failures;
                out.messages.push_back(std::string("the kernel threw: ") + e.what());
            }
            gCurrent = nullptr;
            r.outcomes.push_back(std::move(out));
        }
    }
    r.alpha = Alpha(1);
    return r;
}

}  // namespace phasor::contract

std::string testing::TempDir() { return std::filesystem::temp_directory_path().string() + "/"; }

// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: the harness that runs the generic kernel contract suite
// (tests/materials/kernel_contract_test.cpp) inside the module, for phasor.testing.check_kernel.
//
// The suite's checks are written once, in that file, with GoogleTest's macros; test_materials
// compiles it with GoogleTest, the module compiles the same file with this header instead
// (PHASOR_KERNEL_CONTRACT_HARNESS), which provides the part of GoogleTest the file uses —
// TEST_P fixtures over a parameter, EXPECT_*/ASSERT_* with streamed messages, GTEST_SKIP,
// RecordProperty, HasFailure, TempDir — and records the outcomes in a report instead of printing
// them. So a kernel written in Python is checked by exactly the code that checks the C++ kernels.
// Only what that file needs is here: this is not a test framework.
#pragma once

#include <cmath>
#include <exception>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace phasor::contract {

/// Which cases to run, and how hard (phasor.testing.check_kernel's arguments).
struct Options {
    std::string kernel;
    std::vector<int> lambdas;    // indices into the suite's wavelengths (400, 550, 700 nm); empty: all
    std::vector<int> incidents;  // indices into its incident directions; empty: all
    double sampleScale = 1;      // the statistical checks' sample counts × this (≥ 1000 samples)
    /// Whether an exception must end the run instead of failing a check (KeyboardInterrupt).
    std::function<bool(const std::exception &)> fatal;
};

/// One check of one case: passed, failed (with its messages) or skipped.
struct Outcome {
    std::string check, caseName;
    bool failed = false, skipped = false;
    std::vector<std::string> messages;  // the first few failures (and skip reasons), as gtest prints them
    int failures = 0;
    std::vector<std::pair<std::string, std::string>> properties;  // RecordProperty (p-values …)
};

struct Report {
    std::string kernel;
    std::vector<std::string> cases;
    std::vector<Outcome> outcomes;
    double alpha = 0;  // the Šidák-corrected level each statistical test used
};

// ---- what the test file's macros call ----------------------------------------------------------

/// The outcome being recorded (one check of one case at a time).
Outcome &Current();
/// The options of the run in progress.
const Options &CurrentOptions();
/// The sample count for a nominal `n` under Options::sampleScale.
long long Scaled(long long n);
/// Šidák-corrected level for `testsPerCase` statistical tests in every case of the run.
double Alpha(int testsPerCase);

/// A streamed failure message (GoogleTest's ::testing::Message).
class Message {
  public:
    template <typename T>
    Message &operator<<(const T &v) {
        if constexpr (requires(std::ostream &os) { os << v; }) os_ << v;
        else os_ << "(value)";
        return *this;
    }
    std::string Str() const { return os_.str(); }

  private:
    std::ostringstream os_;
};

/// Records a failure (or a skip) when assigned its message: `Recorder(…) = Message() << …` (the
/// assignment binds after the streaming, so the message is complete).
class Recorder {
  public:
    Recorder(const char *file, int line, std::string what, bool skip = false)
        : file_(file), line_(line), what_(std::move(what)), skip_(skip) {}
    void operator=(const Message &m) const;

  private:
    const char *file_;
    int line_;
    std::string what_;
    bool skip_;
};

template <typename T>
std::string Show(const T &v) {
    std::ostringstream os;
    if constexpr (std::is_same_v<T, std::nullptr_t>) os << "nullptr";
    else if constexpr (std::is_pointer_v<T>) os << (v ? "(non-null)" : "nullptr");
    else if constexpr (requires(std::ostream &o) { o << v; }) os << v;
    else os << "(value)";
    return os.str();
}
/// "a op b" failed: the values, as gtest shows them ("" when it holds).
template <typename A, typename B, typename Op>
std::string Compare(const char *ea, const char *eb, const char *op, const A &a, const B &b, Op holds) {
    if (holds(a, b)) return {};
    return std::string("expected: ") + ea + " " + op + " " + eb + ", actual: " + Show(a) + " vs " + Show(b);
}
template <typename A, typename B, typename C>
std::string Near(const char *ea, const char *eb, const A &a, const B &b, const C &tol) {
    const double d = std::abs(double(a) - double(b));
    if (d <= double(tol)) return {};
    return std::string("the difference between ") + ea + " and " + eb + " is " + Show(d) + ", which exceeds " +
           Show(double(tol)) + " (" + Show(double(a)) + " vs " + Show(double(b)) + ")";
}

// ---- fixtures and their registration -----------------------------------------------------------

class TestBase {
  public:
    virtual ~TestBase() = default;
    virtual void SetUp() {}
    virtual void TearDown() {}
    virtual void TestBody() = 0;
    static bool HasFailure() { return Current().failed; }
    static void RecordProperty(const std::string &key, const std::string &value) {
        Current().properties.emplace_back(key, value);
    }
};

/// The registered checks (TEST_P) of the fixture, in the file's order.
struct Check {
    std::string name;
    std::function<std::unique_ptr<TestBase>()> make;
};
std::vector<Check> &Checks();
inline bool Register(const char *name, std::function<std::unique_ptr<TestBase>()> make) {
    Checks().push_back({name, std::move(make)});
    return true;
}

/// The suite's grid of cases: its wavelengths [m] and incident directions (cos θ, φ).
struct Domain {
    std::vector<double> lambdas;
    std::vector<std::pair<double, double>> incidents;
};

/// Runs every registered check on every case (`setParam` makes a case current, `caseName` names
/// it). A check's exception is its failure, unless Options::fatal says it must end the run.
Report Run(const Options &o, int cases, const std::function<void(int)> &setParam,
           const std::function<std::string(int)> &caseName);

}  // namespace phasor::contract

namespace phasor::test {
/// Defined by the contract file (compiled in harness mode): the suite on one kernel's cases.
contract::Report RunKernelContract(const contract::Options &o);
contract::Domain KernelContractDomain();
}  // namespace phasor::test

// ---- the GoogleTest subset the contract file uses ----------------------------------------------

namespace testing {
template <typename T>
class TestWithParam : public phasor::contract::TestBase {
  public:
    static const T &GetParam() { return *current; }
    static inline const T *current = nullptr;
};
template <typename T>
struct TestParamInfo {
    T param;
    std::size_t index = 0;
};
std::string TempDir();
}  // namespace testing

// `if (ok) {} else …` inside a switch, so that an `else` after the macro cannot bind to it (as gtest).
#define PHASOR_CONTRACT_BLOCKER_ \
    switch (0)                   \
    case 0:                      \
    default:
#define PHASOR_CONTRACT_FAIL_(what, fatal) \
    PHASOR_CONTRACT_FAIL_##fatal(what)
#define PHASOR_CONTRACT_FAIL_0(what) ::phasor::contract::Recorder(__FILE__, __LINE__, what) = ::phasor::contract::Message()
#define PHASOR_CONTRACT_FAIL_1(what) \
    return ::phasor::contract::Recorder(__FILE__, __LINE__, what) = ::phasor::contract::Message()
#define PHASOR_CONTRACT_CHECK_(text, fatal)                                  \
    PHASOR_CONTRACT_BLOCKER_                                                 \
    if (const std::string phasor_contract_why_ = (text); phasor_contract_why_.empty()) { \
    } else                                                                   \
        PHASOR_CONTRACT_FAIL_(phasor_contract_why_, fatal)
#define PHASOR_CONTRACT_BOOL_(cond, expected, fatal) \
    PHASOR_CONTRACT_CHECK_(bool(cond) == expected ? std::string() : std::string("expected ") + #cond + " to be " #expected, fatal)
#define PHASOR_CONTRACT_CMP_(a, b, op, fatal)                                                               \
    PHASOR_CONTRACT_CHECK_(::phasor::contract::Compare(#a, #b, #op, a, b,                                   \
                                                       [](const auto &x, const auto &y) { return x op y; }), \
                           fatal)

#define EXPECT_TRUE(c) PHASOR_CONTRACT_BOOL_(c, true, 0)
#define EXPECT_FALSE(c) PHASOR_CONTRACT_BOOL_(c, false, 0)
#define ASSERT_TRUE(c) PHASOR_CONTRACT_BOOL_(c, true, 1)
#define ASSERT_FALSE(c) PHASOR_CONTRACT_BOOL_(c, false, 1)
#define EXPECT_EQ(a, b) PHASOR_CONTRACT_CMP_(a, b, ==, 0)
#define EXPECT_NE(a, b) PHASOR_CONTRACT_CMP_(a, b, !=, 0)
#define EXPECT_LT(a, b) PHASOR_CONTRACT_CMP_(a, b, <, 0)
#define EXPECT_LE(a, b) PHASOR_CONTRACT_CMP_(a, b, <=, 0)
#define EXPECT_GT(a, b) PHASOR_CONTRACT_CMP_(a, b, >, 0)
#define EXPECT_GE(a, b) PHASOR_CONTRACT_CMP_(a, b, >=, 0)
#define ASSERT_EQ(a, b) PHASOR_CONTRACT_CMP_(a, b, ==, 1)
#define ASSERT_NE(a, b) PHASOR_CONTRACT_CMP_(a, b, !=, 1)
#define ASSERT_LT(a, b) PHASOR_CONTRACT_CMP_(a, b, <, 1)
#define ASSERT_LE(a, b) PHASOR_CONTRACT_CMP_(a, b, <=, 1)
#define ASSERT_GT(a, b) PHASOR_CONTRACT_CMP_(a, b, >, 1)
#define ASSERT_GE(a, b) PHASOR_CONTRACT_CMP_(a, b, >=, 1)
#define EXPECT_NEAR(a, b, tol) PHASOR_CONTRACT_CHECK_(::phasor::contract::Near(#a, #b, a, b, tol), 0)
#define ASSERT_NEAR(a, b, tol) PHASOR_CONTRACT_CHECK_(::phasor::contract::Near(#a, #b, a, b, tol), 1)
#define ASSERT_NO_THROW(stmt)                                                                  \
    PHASOR_CONTRACT_CHECK_(                                                                    \
        [&]() -> std::string {                                                                 \
            try {                                                                              \
                stmt;                                                                          \
                return {};                                                                     \
            } catch (const std::exception &e) {                                                \
                return std::string("expected " #stmt " not to throw; it threw: ") + e.what(); \
            }                                                                                  \
        }(),                                                                                   \
        1)
#define GTEST_SKIP() return ::phasor::contract::Recorder(__FILE__, __LINE__, "skipped", true) = ::phasor::contract::Message()

#define TEST_P(Fixture, Name)                                                                      \
    class Fixture##_##Name##_Check final : public Fixture {                                        \
      public:                                                                                      \
        void TestBody() override;                                                                  \
    };                                                                                             \
    [[maybe_unused]] const bool Fixture##_##Name##_registered = ::phasor::contract::Register(      \
        #Name, [] { return std::unique_ptr<::phasor::contract::TestBase>(new Fixture##_##Name##_Check); }); \
    void Fixture##_##Name##_Check::TestBody()
// Plain tests (the registry's own) are not part of a kernel's contract: compiled, never run.
#define TEST(Suite, Name) [[maybe_unused]] void Suite##_##Name##_NotRun()
#define INSTANTIATE_TEST_SUITE_P(...) static_assert(true, "")
#define GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(...) static_assert(true, "")

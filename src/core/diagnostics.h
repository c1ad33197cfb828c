// SPDX-License-Identifier: Apache-2.0
// phasor — source locations and the diagnostics sink. Library code reports problems here (or
// throws phasor::Error, which the caller turns into a diagnostic); only main() exits.
#pragma once

#include <cstddef>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace phasor {

/// A position in a source file; line and column are 1-based (0 = unknown).
struct FileLoc {
    std::string file;  // as the user wrote it / as opened (may be empty for built-in objects)
    int line = 0;
    int col = 0;
    int length = 1;  // number of source characters to underline
    bool Known() const { return !file.empty(); }
    std::string ToString() const;  // "file:line:col" (or "file" / "<built-in>")
    bool operator==(const FileLoc &) const = default;
};

enum class Severity { Note, Warning, Error };

struct Diagnostic {
    Severity severity = Severity::Error;
    FileLoc loc;
    std::string message;
    std::vector<Diagnostic> notes;  // attached notes (include chain, previous definition, …)
};

/// A user-caused error with a location; thrown by factories and loaders, caught by the builder
/// and the CLI, which turn it into a Diagnostic.
class Error : public std::runtime_error {
  public:
    Error(FileLoc loc, std::string message)
        : std::runtime_error(message), loc_(std::move(loc)), message_(std::move(message)) {}
    explicit Error(std::string message) : Error(FileLoc{}, std::move(message)) {}
    const FileLoc &Loc() const { return loc_; }
    const std::string &Message() const { return message_; }
    std::vector<Diagnostic> notes;

  private:
    FileLoc loc_;
    std::string message_;
};

/// Collects diagnostics. Errors beyond `maxErrors` are counted but not stored. Identical
/// (location, message) pairs are reported once. Warnings become errors when `strict`.
class Diagnostics {
  public:
    explicit Diagnostics(bool strict = false, std::size_t maxErrors = 20)
        : strict_(strict), maxErrors_(maxErrors) {}

    void Report(Diagnostic d);
    void Error(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes = {});
    void Warning(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes = {});
    void Report(const phasor::Error &e) { Error(e.Loc(), e.Message(), e.notes); }

    bool HasErrors() const { return errorCount_ > 0; }
    std::size_t ErrorCount() const { return errorCount_; }
    std::size_t WarningCount() const { return warningCount_; }
    bool TooManyErrors() const { return errorCount_ >= maxErrors_; }
    bool Strict() const { return strict_; }
    const std::vector<Diagnostic> &All() const { return all_; }

    /// Registers a source text so diagnostics can quote the offending line with a caret.
    void AddSource(const std::string &file, std::string text);
    /// Writes every diagnostic in compiler format with source excerpts; `color` adds ANSI colours.
    void Print(std::ostream &os, bool color = false) const;
    /// Formats one diagnostic (and its notes) as Print would.
    std::string Format(const Diagnostic &d, bool color = false) const;

  private:
    bool strict_;
    std::size_t maxErrors_;
    std::size_t errorCount_ = 0, warningCount_ = 0;
    std::vector<Diagnostic> all_;
    std::vector<std::pair<std::string, std::shared_ptr<const std::string>>> sources_;
};

/// Levenshtein distance, for "did you mean …" suggestions.
std::size_t EditDistance(const std::string &a, const std::string &b);
/// The candidate closest to `name` if it is close enough to be a plausible typo, else "".
std::string Suggest(const std::string &name, const std::vector<std::string> &candidates);

}  // namespace phasor

// SPDX-License-Identifier: Apache-2.0
// phasor — source locations and the diagnostics sink. Library code reports problems here (or
// throws phasor::Error, which the caller turns into a diagnostic); only main() exits.
#pragma once

#include <cstddef>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <unordered_set>
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

    /// An error that follows from one already reported (e.g. a reference to a block that failed):
    /// it stops the dependent work, but Diagnostics::Report(const Error &) ignores it, so that one
    /// mistake is reported and counted once.
    static Error Consequence(FileLoc loc) {
        Error e(std::move(loc), "(follows from an error already reported)");
        e.consequence_ = true;
        return e;
    }
    bool IsConsequence() const { return consequence_; }

  private:
    FileLoc loc_;
    std::string message_;
    bool consequence_ = false;
};

/// Collects diagnostics. Errors (and warnings) beyond `maxShown` of each are counted but not
/// stored; Print says how many were left out. Identical (severity, location, message) triples
/// are reported once. Warnings become errors when `strict` (`--strict`). A name that matches
/// nothing (UnknownName) is an error, or a warning when permissive (`--permissive`).
class Diagnostics {
  public:
    explicit Diagnostics(bool strict = false, std::size_t maxShown = 20)
        : strict_(strict), maxShown_(maxShown) {}

    void Report(Diagnostic d);
    void Error(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes = {});
    void Warning(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes = {});
    /// An unknown parameter, or a `-D` that overrides no Define: the value the user meant is
    /// silently not used, so this is an error unless the sink is permissive.
    void UnknownName(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes = {});
    /// Reports a thrown error (nothing for Error::Consequence).
    void Report(const phasor::Error &e) {
        if (!e.IsConsequence()) Error(e.Loc(), e.Message(), e.notes);
    }

    bool HasErrors() const { return errorCount_ > 0; }
    std::size_t ErrorCount() const { return errorCount_; }
    std::size_t WarningCount() const { return warningCount_; }
    /// True once further errors are only counted (callers may then skip costly suggestions).
    bool TooManyErrors() const { return errorCount_ >= maxShown_; }
    bool Strict() const { return strict_; }
    void SetPermissive(bool permissive) { permissive_ = permissive; }
    bool Permissive() const { return permissive_; }
    const std::vector<Diagnostic> &All() const { return all_; }

    /// Registers a source text so diagnostics can quote the offending line with a caret.
    void AddSource(const std::string &file, std::string text);
    /// Writes every diagnostic in compiler format with source excerpts; `color` adds ANSI colours.
    void Print(std::ostream &os, bool color = false) const;
    /// Formats one diagnostic (and its notes) as Print would.
    std::string Format(const Diagnostic &d, bool color = false) const;

  private:
    bool strict_;
    bool permissive_ = false;
    std::size_t maxShown_;
    std::size_t errorCount_ = 0, warningCount_ = 0;
    std::size_t errorsShown_ = 0, warningsShown_ = 0;
    std::vector<Diagnostic> all_;
    std::unordered_set<std::size_t> seen_;  // hashes of every (severity, location, message) reported
    std::vector<std::pair<std::string, std::shared_ptr<const std::string>>> sources_;
};

/// Levenshtein distance, for "did you mean …" suggestions.
std::size_t EditDistance(const std::string &a, const std::string &b);
/// The candidate closest to `name` if it is close enough to be a plausible typo, else "".
std::string Suggest(const std::string &name, const std::vector<std::string> &candidates);
/// A ratio or count for a message, to 3 significant digits ("1.2e+06", "3.5").
std::string FormatRatio(double v);

}  // namespace phasor

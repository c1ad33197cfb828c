// SPDX-License-Identifier: Apache-2.0
#include "core/diagnostics.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

namespace phasor {

std::string FileLoc::ToString() const {
    if (file.empty()) return "<built-in>";
    std::string s = file;
    if (line > 0) {
        s += ":" + std::to_string(line);
        if (col > 0) s += ":" + std::to_string(col);
    }
    return s;
}

void Diagnostics::Report(Diagnostic d) {
    if (d.severity == Severity::Warning && strict_) d.severity = Severity::Error;
    // Duplicates are recognised by a hash, also beyond the shown ones, so the counts are true.
    std::string key = std::to_string(int(d.severity)) + '\n' + d.loc.ToString() + '\n' + d.message;
    if (!seen_.insert(std::hash<std::string>{}(key)).second) return;
    std::size_t *count = &errorCount_, *shown = &errorsShown_;
    if (d.severity == Severity::Warning) count = &warningCount_, shown = &warningsShown_;
    if (d.severity != Severity::Note) {
        ++*count;
        if (*shown >= maxShown_) return;
        ++*shown;
    }
    all_.push_back(std::move(d));
}

void Diagnostics::Error(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes) {
    Report(Diagnostic{Severity::Error, loc, std::move(msg), std::move(notes)});
}

void Diagnostics::Warning(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes) {
    Report(Diagnostic{Severity::Warning, loc, std::move(msg), std::move(notes)});
}

void Diagnostics::UnknownName(const FileLoc &loc, std::string msg, std::vector<Diagnostic> notes) {
    Report(Diagnostic{permissive_ ? Severity::Warning : Severity::Error, loc, std::move(msg), std::move(notes)});
}

void Diagnostics::AddSource(const std::string &file, std::string text) {
    for (auto &s : sources_)
        if (s.first == file) return;
    sources_.emplace_back(file, std::make_shared<const std::string>(std::move(text)));
}

std::string Diagnostics::Format(const Diagnostic &d, bool color) const {
    const char *sev = d.severity == Severity::Error     ? "error"
                      : d.severity == Severity::Warning ? "warning"
                                                        : "note";
    const char *sevColor = d.severity == Severity::Error     ? "\033[1;31m"
                           : d.severity == Severity::Warning ? "\033[1;35m"
                                                             : "\033[1;36m";
    std::ostringstream os;
    if (color) os << "\033[1m";
    os << d.loc.ToString() << ": ";
    if (color) os << sevColor;
    os << sev << ": ";
    if (color) os << "\033[0m";
    os << d.message << "\n";
    // Quote the source line with a caret under the offending text.
    if (d.loc.line > 0) {
        for (const auto &[name, text] : sources_) {
            if (name != d.loc.file) continue;
            std::size_t pos = 0;
            for (int l = 1; l < d.loc.line && pos != std::string::npos; ++l) {
                pos = text->find('\n', pos);
                if (pos != std::string::npos) ++pos;
            }
            if (pos == std::string::npos || pos > text->size()) break;
            std::size_t end = text->find('\n', pos);
            std::string line = text->substr(pos, end == std::string::npos ? std::string::npos : end - pos);
            if (!line.empty() && line.back() == '\r') line.pop_back();
            os << "    " << line << "\n    ";
            // Columns count bytes; keep tabs so the caret lines up.
            int col = std::max(1, d.loc.col);
            for (int i = 1; i < col && i - 1 < (int)line.size(); ++i) os << (line[i - 1] == '\t' ? '\t' : ' ');
            if (color) os << "\033[1;32m";
            os << '^';
            for (int i = 1; i < d.loc.length; ++i) os << '~';
            if (color) os << "\033[0m";
            os << "\n";
            break;
        }
    }
    for (const Diagnostic &n : d.notes) os << Format(n, color);
    return os.str();
}

void Diagnostics::Print(std::ostream &os, bool color) const {
    for (const Diagnostic &d : all_) os << Format(d, color);
    auto more = [&](std::size_t n, const char *what) {
        if (n > 0) os << n << " more " << what << (n == 1 ? "" : "s") << " not shown\n";
    };
    more(errorCount_ - errorsShown_, "error");
    more(warningCount_ - warningsShown_, "warning");
}

std::size_t EditDistance(const std::string &a, const std::string &b) {
    // Optimal string alignment distance: insertions, deletions, substitutions and swaps of two
    // adjacent characters each cost 1 (so "widht" is one edit from "width").
    std::vector<std::size_t> prev2(b.size() + 1), prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        cur[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                cur[j] = std::min(cur[j], prev2[j - 2] + 1);
        }
        std::swap(prev2, prev);
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

std::string FormatRatio(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

std::string Suggest(const std::string &name, const std::vector<std::string> &candidates) {
    std::string best;
    std::size_t bestD = std::string::npos;
    // A difference of case alone counts as one edit ("cu2o" → "Cu2O", "bk7" → "BK7").
    auto lower = [](std::string s) {
        for (char &ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
        return s;
    };
    const std::string folded = lower(name);
    for (const std::string &c : candidates) {
        std::size_t d = EditDistance(name, c);
        if (d > 1 && lower(c) == folded) d = 1;
        if (d < bestD) { bestD = d; best = c; }
    }
    // Accept up to a third of the name's length (at least 1, at most 3 edits).
    std::size_t limit = std::clamp<std::size_t>(name.size() / 3, 1, 3);
    return bestD <= limit ? best : std::string();
}

}  // namespace phasor

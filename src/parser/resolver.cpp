// SPDX-License-Identifier: Apache-2.0
// phasor — .wscene resolver: FileAst → SceneDesc (docs/wscene.md §5–§7). Follows Includes,
// substitutes $defines (and -D overrides), evaluates dimensioned arithmetic and math functions,
// converts to SI, applies `enabled`, and checks names and @references.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "core/units.h"
#include "parser/ast.h"
#include "parser/eval.h"
#include "parser/parser.h"

namespace phasor {

namespace wscene {

// "256 MiB", or "2000 bytes" if not a whole number of MiB.
std::string SizeText(std::size_t bytes) {
    const std::size_t mib = std::size_t(1) << 20;
    return bytes % mib == 0 ? std::to_string(bytes / mib) + " MiB" : std::to_string(bytes) + " bytes";
}

FileText FileText::TooLarge(std::size_t limit) {
    return {std::nullopt,
            "it is larger than the limit of " + SizeText(limit) + " for a scene (put large meshes in mesh files)",
            true};
}

FileText ReadSceneText(const std::string &path, std::size_t limit) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::file_status st = fs::status(path, ec);
    switch (st.type()) {
        case fs::file_type::regular: break;
        case fs::file_type::not_found: return {std::nullopt, "no such file"};
        case fs::file_type::directory: return {std::nullopt, "it is a directory"};
        case fs::file_type::character:
        case fs::file_type::block: return {std::nullopt, "it is a device, not a regular file"};
        case fs::file_type::fifo: return {std::nullopt, "it is a pipe (FIFO), not a regular file"};
        case fs::file_type::socket: return {std::nullopt, "it is a socket, not a regular file"};
        default: return {std::nullopt, ec ? ec.message() : "it is not a regular file"};
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > limit) return FileText::TooLarge(limit);
    std::ifstream in(path, std::ios::binary);
    if (!in) return {std::nullopt, std::strerror(errno)};
    std::string text;
    if (!ec) text.reserve(std::size_t(size));
    char buf[1 << 16];
    // The size may have changed since it was asked: the limit holds for what is read.
    while (in.read(buf, sizeof buf) || in.gcount() > 0) {
        text.append(buf, std::size_t(in.gcount()));
        if (text.size() > limit) return FileText::TooLarge(limit);
    }
    if (in.bad()) return {std::nullopt, "read error"};
    return {std::move(text), ""};
}

}  // namespace wscene

namespace {

using wscene::Expr;
using wscene::FileText;
using wscene::FileAst;
using wscene::Pos;
using wscene::Stmt;

const char *kCommandLine = "<command line>";

struct DefineInfo {
    std::optional<Value> value;  // nullopt: its definition failed (already reported)
    FileLoc site;                // the name in the Define statement
};

struct Override {
    std::string name, text;
    FileLoc nameLoc;  // in <command line>
    int line = 0, valueCol = 0;
    bool used = false;
};

struct NameInfo {
    std::string keyword, type;
    FileLoc loc;
    bool disabled = false, broken = false;
    FileLoc enabledLoc;
};

class Resolver {
  public:
    Resolver(const ParseOptions &opt, Diagnostics &diag) : opt_(opt), diag_(diag), eval_(diag) {
        eval_.lookupVar = [this](const Expr &e, const FileLoc &loc) { return LookupVar(e, loc); };
        eval_.notesFor = [this](const std::string &file) { return ChainOf(file); };
    }

    std::optional<SceneDesc> Run(const std::string *text, const std::string &fileName) {
        std::size_t errorsBefore = diag_.ErrorCount();
        PrepareOverrides();
        FileText content;
        if (text)
            content = text->size() <= opt_.maxSceneBytes ? FileText{*text, ""} : FileText::TooLarge(opt_.maxSceneBytes);
        else
            content = Read(fileName);
        if (!content.text) {
            diag_.Error(FileLoc{fileName, 0, 0, 1}, "cannot read scene file '" + fileName + "': " + Why(content));
            return std::nullopt;
        }
        textBytes_ = content.text->size();
        desc_.sourceFile = fileName;
        // Every block has a '{': a cheap upper bound that avoids regrowing a large entity list.
        desc_.entities.reserve(
            std::min<std::size_t>(std::count(content.text->begin(), content.text->end(), '{'), 1u << 22));
        stack_.push_back(Key(fileName));
        ProcessFile(*content.text, fileName);
        stack_.pop_back();
        Finish();
        if (diag_.ErrorCount() != errorsBefore) {
            if (!opt_.partial) return std::nullopt;
            desc_.incomplete = true;
        }
        desc_.namesLost = lostNames_;
        for (const auto &[name, info] : names_)
            if (info.broken) desc_.unavailable.insert(name);
        return std::move(desc_);
    }

  private:
    // ---- files and includes ----------------------------------------------------------------
    // Reads a file of at most what is left of the scene's text budget.
    FileText Read(const std::string &path) {
        const std::size_t left = opt_.maxSceneBytes - std::min(opt_.maxSceneBytes, textBytes_);
        if (!opt_.readFile) return wscene::ReadSceneText(path, left);
        std::optional<std::string> text = opt_.readFile(path);
        if (!text) return {std::nullopt, "no such file"};
        if (text->size() > left) return FileText::TooLarge(left);
        return {std::move(text), ""};
    }
    std::string Why(const FileText &f) const {
        if (!f.tooLarge || textBytes_ == 0) return f.problem;
        return "the scene's text (every file, every Include expansion) would exceed the limit of " +
               wscene::SizeText(opt_.maxSceneBytes);
    }
    // "a.wscene → b.wscene → …" for the files being read.
    std::string Chain() const {
        std::string chain;
        for (const std::string &f : stack_) chain += (chain.empty() ? "" : " → ") + f;
        return chain;
    }
    static std::string Key(const std::string &path) {
        return std::filesystem::path(path).lexically_normal().generic_string();
    }
    std::vector<Diagnostic> ChainOf(const std::string &file) const {
        auto it = chains_.find(file);
        return it == chains_.end() ? std::vector<Diagnostic>{} : it->second;
    }
    void Err(const FileLoc &loc, const std::string &msg, std::vector<Diagnostic> notes = {}) {
        for (const Diagnostic &n : ChainOf(loc.file)) notes.push_back(n);
        diag_.Error(loc, msg, std::move(notes));
    }
    void Warn(const FileLoc &loc, const std::string &msg, std::vector<Diagnostic> notes = {}) {
        for (const Diagnostic &n : ChainOf(loc.file)) notes.push_back(n);
        diag_.Warning(loc, msg, std::move(notes));
    }
    static Diagnostic Note(const FileLoc &loc, std::string msg) {
        return Diagnostic{Severity::Note, loc, std::move(msg), {}};
    }
    FileLoc Loc(const std::string &file, const Pos &p) const {
        return FileLoc{file, p.line, p.col, std::max(1, p.length)};
    }

    void ProcessFile(const std::string &text, const std::string &file) {
        diag_.AddSource(file, text);
        FileAst ast;
        // Statements are resolved as they are parsed (no whole-file tree).
        wscene::ParseFileAst(text, file, diag_, ast, ChainOf(file), [&](Stmt &st) {
            switch (st.kind) {
                case Stmt::Kind::Header:
                    CheckHeader(st, file);
                    break;
                case Stmt::Kind::Include:
                    DoInclude(st, file);
                    break;
                case Stmt::Kind::Define:
                    DoDefine(st, file);
                    break;
                case Stmt::Kind::Block:
                    DoBlock(st, file);
                    break;
            }
        });
        if (ast.lexError) lostNames_ = true;
    }

    void CheckHeader(const Stmt &st, const std::string &file) {
        if (st.text.empty()) return;  // reported by the syntax pass
        if (st.text == "1" || st.text == "2")
            fileVersion_[file] = st.text[0] - '0';
        else
            Err(Loc(file, st.textPos), "unsupported format version 'wscene " + st.text +
                                           "' (this phasor reads versions 1 and 2; it writes 2)");
    }

    void DoInclude(const Stmt &st, const std::string &file) {
        FileLoc at = Loc(file, st.textPos);
        if (st.text.empty()) {
            Err(at, "empty file name in Include");
            return;
        }
        std::string target = (std::filesystem::path(file).parent_path() / std::filesystem::path(st.text))
                                 .lexically_normal()
                                 .generic_string();
        std::string key = Key(target);
        for (std::size_t k = 0; k < stack_.size(); ++k) {
            if (stack_[k] != key) continue;
            std::string cycle;
            for (std::size_t m = k; m < stack_.size(); ++m) cycle += stack_[m] + " → ";
            Err(at, "include cycle: '" + st.text + "' is already being read (" + cycle + key + ")");
            return;
        }
        if ((int)stack_.size() > opt_.maxIncludeDepth) {
            Err(at,
                "includes nested too deeply (more than " + std::to_string(opt_.maxIncludeDepth) + " levels)");
            return;
        }
        // After a limit was reached, the remaining Includes are skipped (reported once).
        if (limitReached_) return;
        if (++includes_ > opt_.maxIncludes) {
            Err(at, "too many Include expansions (more than " + std::to_string(opt_.maxIncludes) +
                        " in one scene; files that include others several times multiply): " + Chain() +
                        " → " + key);
            limitReached_ = lostNames_ = true;
            return;
        }
        FileText content = Read(target);
        if (!content.text) {
            Err(at, "cannot read included file '" + st.text + "' (looked for " + target + "): " + Why(content) +
                        (content.tooLarge ? " (" + Chain() + " → " + key + ")" : ""));
            if (content.tooLarge) limitReached_ = lostNames_ = true;
            return;
        }
        textBytes_ += content.text->size();
        // The include chain of the new file: this Include, then this file's own chain.
        if (!chains_.count(target)) {
            std::vector<Diagnostic> chain = {Note(Loc(file, st.pos), "included from here")};
            for (const Diagnostic &n : ChainOf(file)) chain.push_back(n);
            chains_[target] = std::move(chain);
        }
        stack_.push_back(key);
        ProcessFile(*content.text, target);
        stack_.pop_back();
    }

    // ---- Define and -D ---------------------------------------------------------------------
    void PrepareOverrides() {
        std::string source;
        int line = 0;
        for (const auto &[name, text] : opt_.defines) {
            ++line;
            std::string shown = "-D " + name + "=" + text;
            for (char &c : shown)
                if (c == '\n' || c == '\r') c = ' ';
            source += shown + "\n";
            Override ov;
            ov.name = name;
            ov.text = text;
            ov.line = line;
            ov.valueCol = int(name.size()) + 5;
            ov.nameLoc = FileLoc{kCommandLine, line, 4, std::max(1, int(name.size()))};
            if (!wscene::IsIdentifier(name) || wscene::IsReservedWord(name)) {
                diag_.Error(ov.nameLoc, "'-D " + name + "': '" + name + "' is not a valid variable name");
                continue;
            }
            bool dup = false;
            for (const Override &o : overrides_)
                if (o.name == name) {
                    diag_.Error(ov.nameLoc, "'-D " + name + "' is given twice",
                                {Note(o.nameLoc, "first given here")});
                    dup = true;
                }
            if (!dup) overrides_.push_back(std::move(ov));
        }
        if (!opt_.defines.empty()) diag_.AddSource(kCommandLine, source);
    }

    std::optional<Value> EvalOverride(Override &ov, const std::optional<Value> &def) {
        FileLoc valueLoc{kCommandLine, ov.line, ov.valueCol, std::max(1, int(ov.text.size()))};
        // A Define holding a string takes the -D text as the string (quotes optional).
        if (def && def->kind == Value::Kind::String) {
            Diagnostics scratch;
            Expr e;
            if (wscene::ParseExprAst(ov.text, kCommandLine, ov.line, ov.valueCol, scratch, e) &&
                e.kind == Expr::Kind::String)
                return Value::String(e.text, valueLoc);
            return Value::String(ov.text, valueLoc);
        }
        Expr e;
        if (!wscene::ParseExprAst(ov.text, kCommandLine, ov.line, ov.valueCol, diag_, e)) return std::nullopt;
        std::optional<Value> v = eval_.Eval(e, kCommandLine);
        // A quoted quantity ("150 um") is read as the quantity.
        if (v && v->kind == Value::Kind::String && !(def && def->kind == Value::Kind::String)) {
            Expr inner;
            Diagnostics scratch;
            if (wscene::ParseExprAst(v->text, kCommandLine, ov.line, ov.valueCol + 1, scratch, inner)) {
                std::optional<Value> w = eval_.Eval(inner, kCommandLine);
                if (w) v = w;
            }
        }
        if (v) v->loc = valueLoc;
        return v;
    }

    static bool Compatible(const Value &def, const Value &v) {
        using K = Value::Kind;
        switch (def.kind) {
            case K::Number:
                return v.kind == K::Number && v.dim == def.dim;
            case K::Complex:
                return v.kind == K::Complex || (v.kind == K::Number && v.dim.IsNone());
            case K::List:
                if (v.kind != K::List) return false;
                if (!def.items.empty() && !v.items.empty() && def.items[0].kind == K::Number &&
                    v.items[0].kind == K::Number)
                    return def.items[0].dim == v.items[0].dim;
                return true;
            default:
                return v.kind == def.kind;
        }
    }

    void DoDefine(const Stmt &st, const std::string &file) {
        FileLoc site = Loc(file, st.namePos);
        auto it = defines_.find(st.name);
        if (it != defines_.end()) {
            Err(site, "redefinition of '$" + st.name + "'", {Note(it->second.site, "first defined here")});
            return;
        }
        DefineInfo info;
        info.site = site;
        if (!st.broken) info.value = eval_.Eval(st.value, file);
        for (Override &ov : overrides_) {
            if (ov.name != st.name) continue;
            ov.used = true;
            if (st.broken) break;
            std::optional<Value> v = EvalOverride(ov, info.value);
            if (!v || !info.value) {
                info.value = std::nullopt;
                break;
            }
            if (v->kind == Value::Kind::Number && v->dim.IsNone() && info.value->kind == Value::Kind::Number &&
                std::find(opt_.siDefines.begin(), opt_.siDefines.end(), st.name) != opt_.siDefines.end()) {
                v->dim = info.value->dim;  // a number in SI units (ParseOptions::siDefines)
                v->isInteger = v->isInteger && v->dim.IsNone();
            }
            if (!Compatible(*info.value, *v)) {
                const Value &d = *info.value;
                std::string want = d.kind == Value::Kind::Number ? d.dim.Describe() : d.DescribeKind();
                if (d.kind == Value::Kind::List && !d.items.empty() && d.items[0].kind == Value::Kind::Number)
                    want = "a list of " +
                           d.items[0].dim.Describe().substr(d.items[0].dim.Describe().find(' ') + 1) + "s";
                diag_.Error(v->loc,
                            "'-D " + st.name + "' must be " + want + ", like the Define it overrides; got " +
                                v->DescribeKind() + " (" + v->ToString() + ")",
                            {Note(site, "'" + st.name + "' is defined here as " + d.ToString())});
                info.value = std::nullopt;
                break;
            }
            info.value = v;
            break;
        }
        defines_.emplace(st.name, std::move(info));
    }

    std::optional<Value> LookupVar(const Expr &e, const FileLoc &loc) {
        auto it = defines_.find(e.text);
        if (it == defines_.end()) {
            pendingVars_.push_back({e.text, loc});
            return std::nullopt;
        }
        if (!it->second.value) return std::nullopt;  // its Define failed; already reported
        Value v = *it->second.value;
        v.loc = loc;
        return v;
    }

    // ---- blocks ----------------------------------------------------------------------------
    void DoBlock(const Stmt &st, const std::string &file) {
        FileLoc kwLoc = Loc(file, st.pos);
        FileLoc nameLoc = st.hasName ? Loc(file, st.namePos) : kwLoc;
        bool ok = !st.broken;
        if (st.keyword == "Render") {
            if (renderSeen_) {
                Err(kwLoc, "only one Render block is allowed",
                    {Note(renderLoc_, "the first Render block is here")});
                ok = false;
            } else {
                renderSeen_ = true;
                renderLoc_ = kwLoc;
            }
        }
        if (st.hasType && st.text.empty()) {
            Err(Loc(file, st.textPos), "empty plug-in type for " + st.keyword);
            ok = false;
        }
        NameInfo *named = nullptr;
        if (st.hasName) {
            if (!wscene::IsIdentifier(st.name)) {
                Err(nameLoc,
                    "invalid name \"" + st.name +
                        "\": names are letters, digits and '_' (not starting with a digit) so that @name "
                        "can refer to them");
                ok = false;
            } else if (auto it = names_.find(st.name); it != names_.end()) {
                Err(nameLoc,
                    "duplicate name '" + st.name + "': already used by " + it->second.keyword + " \"" +
                        it->second.type + "\"",
                    {Note(it->second.loc, "'" + st.name + "' is first defined here")});
                ok = false;
            } else {
                NameInfo info{st.keyword, st.text, nameLoc, false, st.broken, {}};
                named = &names_.emplace(st.name, info).first->second;
            }
        }
        if (st.broken) return;

        SceneEntity ent;
        ent.keyword = st.keyword;
        ent.type = st.text;
        ent.name = st.hasName ? st.name : "";
        ent.loc = kwLoc;
        ent.nameLoc = nameLoc;
        ent.params = ParamDict(kwLoc);
        if (const auto v = fileVersion_.find(file); v != fileVersion_.end()) ent.params.SetFormatVersion(v->second);
        bool enabled = true;
        // Blocks have a handful of parameters: a linear scan beats a map (no allocation).
        std::vector<const wscene::ParamNode *> seen;
        seen.reserve(st.params.size());
        for (const wscene::ParamNode &p : st.params) {
            FileLoc pLoc = Loc(file, p.namePos);
            auto first = std::find_if(seen.begin(), seen.end(),
                                      [&](const wscene::ParamNode *q) { return q->name == p.name; });
            if (first != seen.end()) {
                Err(pLoc, "duplicate parameter '" + p.name + "'",
                    {Note(Loc(file, (*first)->namePos), "'" + p.name + "' is first given here")});
                ok = false;
                continue;
            }
            seen.push_back(&p);
            std::optional<Value> v = eval_.Eval(p.value, file);
            if (!v) {
                ok = false;
                continue;
            }
            if (p.name == "enabled") {
                if (v->kind != Value::Kind::Bool) {
                    Err(v->loc,
                        "'enabled' must be a boolean expression (true, false, or e.g. $mode == \"fast\"); "
                        "got " +
                            v->DescribeKind());
                    ok = false;
                    continue;
                }
                enabled = v->boolean;
                if (!enabled && named) {
                    named->disabled = true;
                    named->enabledLoc = pLoc;
                }
                continue;
            }
            ent.params.Add(p.name, std::move(*v), pLoc);
        }
        if (!ok) {
            if (named) named->broken = true;
            return;
        }
        if (enabled) desc_.entities.push_back(std::move(ent));
    }

    // ---- after everything was read ---------------------------------------------------------
    void Finish() {
        for (const Override &ov : overrides_) {
            if (ov.used || lostNames_) continue;  // (its Define may have been in the part not read)
            std::string sug = Suggest(ov.name, DefineNames());
            diag_.UnknownName(ov.nameLoc, "'-D " + ov.name + "' does not override any Define in the scene" +
                                              (sug.empty() ? "" : "; did you mean '" + sug + "'?"));
        }
        for (const auto &[name, loc] : pendingVars_) {
            auto it = defines_.find(name);
            if (it != defines_.end()) {
                Err(loc, "'$" + name + "' is used before its Define",
                    {Note(it->second.site, "defined here")});
                continue;
            }
            std::string sug = Suggest(name, DefineNames());
            std::vector<Diagnostic> notes;
            for (const Override &ov : overrides_)
                if (ov.name == name)
                    notes.push_back(Note(ov.nameLoc, "-D only overrides a Define; add 'Define " + name +
                                                         " = …' to the scene"));
            Err(loc, "'$" + name + "' is not defined" + (sug.empty() ? "" : "; did you mean '$" + sug + "'?"),
                std::move(notes));
        }
        for (const SceneEntity &e : desc_.entities)
            for (const Param &p : e.params.All()) CheckRefs(p.value);
    }

    std::vector<std::string> DefineNames() const {
        std::vector<std::string> names;
        for (const auto &d : defines_) names.push_back(d.first);
        std::sort(names.begin(), names.end());
        return names;
    }

    void CheckRefs(const Value &v) {
        if (v.kind == Value::Kind::Ref) {
            auto it = names_.find(v.text);
            if (it == names_.end()) {
                if (lostNames_) return;  // the name may have been in a part lost to a lexical error
                desc_.unavailable.insert(v.text);
                if (sortedNames_.empty()) {
                    for (const auto &n : names_) sortedNames_.push_back(n.first);
                    std::sort(sortedNames_.begin(), sortedNames_.end());  // deterministic choice among equals
                }
                std::string sug = diag_.TooManyErrors() ? "" : Suggest(v.text, sortedNames_);
                std::string msg = "'@" + v.text + "' is not defined";
                if (!sug.empty()) {
                    const NameInfo &s = names_.at(sug);
                    msg += "; did you mean '@" + sug + "' (" + s.keyword + " \"" + s.type + "\" at " +
                           s.loc.ToString() + ")?";
                }
                Err(v.loc, msg);
                return;
            }
            const NameInfo &n = it->second;
            if (n.disabled) {
                desc_.unavailable.insert(v.text);
                Err(v.loc,
                    "'@" + v.text + "' refers to " + n.keyword + " \"" + n.type + "\", which is disabled",
                    {Note(n.enabledLoc, "disabled here")});
            }
            return;
        }
        for (const Value &it : v.items) CheckRefs(it);
    }

    const ParseOptions &opt_;
    Diagnostics &diag_;
    wscene::Evaluator eval_;
    SceneDesc desc_;
    std::vector<std::string> stack_;                         // files being read (include cycle detection)
    std::map<std::string, std::vector<Diagnostic>> chains_;  // file → "included from" notes
    std::map<std::string, int> fileVersion_;                  // file → its `wscene N` header
    std::unordered_map<std::string, DefineInfo> defines_;
    std::vector<Override> overrides_;
    std::vector<std::pair<std::string, FileLoc>> pendingVars_;
    std::unordered_map<std::string, NameInfo> names_;
    bool renderSeen_ = false;
    FileLoc renderLoc_;
    bool lostNames_ = false;       // names may be missing: text or an Include was skipped
    std::size_t includes_ = 0;     // Include expansions so far
    std::size_t textBytes_ = 0;    // text read so far (every file, every expansion)
    bool limitReached_ = false;    // maxIncludes or maxSceneBytes: later Includes are skipped
    std::vector<std::string> sortedNames_;  // names_, for suggestions (made on first need)
};

}  // namespace

std::optional<SceneDesc> ParseSceneFile(const std::string &path, const ParseOptions &options,
                                        Diagnostics &diag) {
    return Resolver(options, diag).Run(nullptr, path);
}

std::optional<SceneDesc> ParseSceneFile(const std::string &path, const DefineList &defines,
                                        Diagnostics &diag) {
    ParseOptions o;
    o.defines = defines;
    return ParseSceneFile(path, o, diag);
}

std::optional<SceneDesc> ParseSceneString(const std::string &text, const std::string &virtualFileName,
                                          const ParseOptions &options, Diagnostics &diag) {
    return Resolver(options, diag).Run(&text, virtualFileName);
}

std::optional<SceneDesc> ParseSceneString(const std::string &text, const std::string &virtualFileName,
                                          const DefineList &defines, Diagnostics &diag) {
    ParseOptions o;
    o.defines = defines;
    return ParseSceneString(text, virtualFileName, o, diag);
}

std::optional<std::pair<std::string, std::string>> SplitDefineArgument(const std::string &arg,
                                                                       Diagnostics &diag) {
    std::size_t eq = arg.find('=');
    FileLoc loc{kCommandLine, 0, 0, 1};
    if (eq == std::string::npos) {
        diag.Error(loc, "'-D " + arg + "': expected name=value");
        return std::nullopt;
    }
    std::string name = arg.substr(0, eq);
    while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.pop_back();
    if (!wscene::IsIdentifier(name)) {
        diag.Error(loc, "'-D " + arg + "': '" + name + "' is not a valid variable name");
        return std::nullopt;
    }
    return std::make_pair(name, arg.substr(eq + 1));
}

std::optional<Value> ParseValueString(const std::string &text, const std::string &virtualFileName,
                                      Diagnostics &diag) {
    diag.AddSource(virtualFileName, text);
    Expr e;
    if (!wscene::ParseExprAst(text, virtualFileName, 1, 1, diag, e)) return std::nullopt;
    wscene::Evaluator ev(diag);
    ev.lookupVar = [&](const Expr &x, const FileLoc &loc) -> std::optional<Value> {
        diag.Error(loc, "'$" + x.text + "' is not defined");
        return std::nullopt;
    };
    return ev.Eval(e, virtualFileName);
}

bool SameScene(const SceneDesc &a, const SceneDesc &b, std::string *why) {
    auto fail = [&](const std::string &m) {
        if (why) *why = m;
        return false;
    };
    if (a.entities.size() != b.entities.size())
        return fail("entity count " + std::to_string(a.entities.size()) + " vs " +
                    std::to_string(b.entities.size()));
    for (std::size_t i = 0; i < a.entities.size(); ++i) {
        const SceneEntity &x = a.entities[i], &y = b.entities[i];
        std::string at =
            "entity " + std::to_string(i) + " (" + x.keyword + " \"" + x.type + "\" \"" + x.name + "\")";
        if (x.keyword != y.keyword || x.type != y.type || x.name != y.name)
            return fail(at + " vs " + y.keyword + " \"" + y.type + "\" \"" + y.name + "\"");
        const auto &px = x.params.All(), &py = y.params.All();
        if (px.size() != py.size()) return fail(at + ": parameter count differs");
        for (std::size_t k = 0; k < px.size(); ++k) {
            if (px[k].name != py[k].name) return fail(at + ": parameter " + px[k].name + " vs " + py[k].name);
            if (!px[k].value.SameAs(py[k].value))
                return fail(at + ": '" + px[k].name + "' = " + px[k].value.ToString() + " vs " +
                            py[k].value.ToString());
        }
    }
    return true;
}

}  // namespace phasor

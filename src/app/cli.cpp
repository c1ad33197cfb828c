// SPDX-License-Identifier: Apache-2.0
#include "app/cli.h"

#include "core/diagnostics.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace phasor {

namespace {
template <typename T>
bool ParseInt(const std::string &s, T &out) {
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && p == s.data() + s.size();
}
// A finite decimal number, the whole string.
bool ParseDouble(const std::string &s, double &out) {
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return false;
    char *end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}
// One of render's options at scale (docs/distributed.md): --sweep NAME=v1,v2,…, --checkpoint SECONDS,
// --resume FILE.
bool ParseRunOption(const std::string &flag, const std::string &v, CliOptions::RunOptions &run, std::string &err) {
    if (flag == "--checkpoint") {
        if (!ParseDouble(v, run.checkpoint) || !(run.checkpoint > 0)) {
            err = "'--checkpoint' expects a positive number of seconds; got '" + v + "'";
            return false;
        }
        return true;
    }
    if (flag == "--resume") {
        run.resume = v;
        return true;
    }
    // NAME=v1,v2,…: commas inside (), [] or quotes belong to a value (rotate(90 deg, [1 0 0])).
    const std::size_t eq = v.find('=');
    const std::string name = eq == std::string::npos ? "" : v.substr(0, eq);
    std::vector<std::string> values;
    if (!name.empty()) {
        std::string cur;
        int depth = 0;
        bool quoted = false;
        for (std::size_t k = eq + 1; k <= v.size(); ++k) {
            const char c = k < v.size() ? v[k] : ',';
            if (c == '"') quoted = !quoted;
            else if (!quoted && (c == '(' || c == '[')) ++depth;
            else if (!quoted && (c == ')' || c == ']')) --depth;
            if (c == ',' && depth == 0 && !quoted) {
                values.push_back(cur);
                cur.clear();
            } else {
                cur += c;
            }
        }
    }
    if (name.empty() || std::any_of(values.begin(), values.end(), [](const std::string &x) { return x.empty(); })) {
        err = "'--sweep' expects NAME=value1,value2,… (a Define and its values); got '" + v + "'";
        return false;
    }
    for (const auto &[n, vals] : run.sweeps)
        if (n == name) {
            err = "'--sweep' names '" + name + "' twice (give all its values in one --sweep)";
            return false;
        }
    for (std::size_t i = 0; i < values.size(); ++i)
        if (std::find(values.begin(), values.begin() + std::ptrdiff_t(i), values[i]) != values.begin() + std::ptrdiff_t(i)) {
            err = "'--sweep " + name + "' lists the value '" + values[i] + "' twice";
            return false;
        }
    run.sweeps.emplace_back(name, std::move(values));
    return true;
}

// The combinations render's options at scale allow.
bool CheckRunOptions(const CliOptions &o, std::string &err) {
    const auto &run = o.run;
    if (!run.sweeps.empty() && (!run.resume.empty() || run.checkpoint > 0)) {
        err = std::string("'--sweep' renders several images; '") + (run.resume.empty() ? "--checkpoint" : "--resume") +
              "' is for one render (render each value on its own to checkpoint it)";
        return false;
    }
    for (const auto &[name, values] : run.sweeps)
        for (const auto &d : o.defines)
            if (d.first == name) {
                err = "'" + name + "' is given both by -D and by --sweep";
                return false;
            }
    return true;
}

}  // namespace

bool ParseCommandLine(int argc, char **argv, CliOptions &o, std::string &err) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        err = "no command given";
        return false;
    }
    std::size_t i = 0;
    const std::string cmd = args[i++];
    static const std::vector<std::pair<std::string, Command>> commands = {
        {"render", Command::Render}, {"check", Command::Check},       {"format", Command::Format},
        {"list", Command::List},     {"describe", Command::Describe}, {"profile", Command::Profile},
        {"probe", Command::Probe},   {"compare", Command::Compare},   {"help", Command::Help},
        {"--help", Command::Help},   {"-h", Command::Help},           {"--version", Command::Version}};
    auto known = std::find_if(commands.begin(), commands.end(), [&](const auto &c) { return c.first == cmd; });
    if (known == commands.end()) {
        std::vector<std::string> names;
        for (const auto &c : commands) names.push_back(c.first);
        const std::string sug = Suggest(cmd, names);
        err = "unknown command '" + cmd + "'" + (sug.empty() ? "" : "; did you mean '" + sug + "'?");
        return false;
    }
    o.command = known->second;
    std::vector<std::string> positional;
    auto value = [&](const std::string &flag, std::string &out) {
        if (i >= args.size()) {
            err = "'" + flag + "' needs a value";
            return false;
        }
        out = args[i++];
        return true;
    };
    while (i < args.size()) {
        std::string a = args[i++], v;
        if (a == "-o" || a == "--output") { if (!value(a, o.output)) return false; }
        else if (a == "--integrator") { if (!value(a, o.integrator)) return false; }
        else if (a == "--sampler") { if (!value(a, o.sampler)) return false; }
        else if (a == "--spp" || a == "--threads" || a == "--seed") {
            if (!value(a, v)) return false;
            bool ok = a == "--spp" ? ParseInt(v, o.spp) && o.spp > 0
                      : a == "--threads" ? ParseInt(v, o.threads) && o.threads >= 0
                                         : ParseInt(v, o.seed) && o.seed >= 0;
            if (!ok) {
                err = "'" + a + "' expects a non-negative whole number" + std::string(a == "--spp" ? " (≥ 1)" : "") +
                      "; got '" + v + "'";
                return false;
            }
        } else if (a == "-D" || a.rfind("-D", 0) == 0) {
            std::string def = a == "-D" ? "" : a.substr(2);
            if (a == "-D" && !value(a, def)) return false;
            auto eq = def.find('=');
            if (eq == std::string::npos || eq == 0) {
                err = "'-D' expects name=value; got '" + def + "'";
                return false;
            }
            o.defines.emplace_back(def.substr(0, eq), def.substr(eq + 1));
        } else if (o.command == Command::Render && (a == "--sweep" || a == "--checkpoint" || a == "--resume")) {
            if (!value(a, v) || !ParseRunOption(a, v, o.run, err)) return false;
        } else if (o.command == Command::Compare &&
                   (a == "--integrators" || a == "--reference" || a == "--reference-integrator")) {
            if (!value(a, v)) return false;
            auto &c = o.compare;
            if (a == "--integrators") {
                std::size_t start = 0;
                for (;;) {
                    const std::size_t comma = v.find(',', start);
                    const std::string name =
                        v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
                    if (name.empty()) {
                        err = "'--integrators' expects names separated by commas (e.g. grt,ray); got '" + v + "'";
                        return false;
                    }
                    if (std::find(c.integrators.begin(), c.integrators.end(), name) != c.integrators.end()) {
                        err = "'--integrators' names '" + name + "' twice";
                        return false;
                    }
                    c.integrators.push_back(name);
                    if (comma == std::string::npos) break;
                    start = comma + 1;
                }
            } else if (a == "--reference") c.reference = v;
            else c.referenceIntegrator = v;
        } else if (o.command == Command::Compare && (a == "--time" || a == "--reference-spp")) {
            if (!value(a, v)) return false;
            auto &c = o.compare;
            if (a == "--time") {
                if (!ParseDouble(v, c.seconds) || !(c.seconds > 0)) {
                    err = "'--time' expects a positive number of seconds; got '" + v + "'";
                    return false;
                }
            } else if (!ParseInt(v, c.referenceSpp) || c.referenceSpp < 1) {
                err = "'--reference-spp' expects a whole number ≥ 1; got '" + v + "'";
                return false;
            }
        } else if ((o.command == Command::Compare || o.command == Command::Profile) &&
                   (a == "--row" || a == "--column")) {
            if (!value(a, v)) return false;
            int n = -1;
            if (!ParseInt(v, n) || n < 0) {
                err = "'" + a + "' expects a non-negative whole number; got '" + v + "'";
                return false;
            }
            int &row = o.command == Command::Compare ? o.compare.row : o.profile.row;
            int &column = o.command == Command::Compare ? o.compare.column : o.profile.column;
            (a == "--row" ? row : column) = n;
            if (row >= 0 && column >= 0) {
                err = "'--row' and '--column' exclude each other (one profile per run)";
                return false;
            }
        } else if (o.command == Command::Profile && (a == "--channel" || a == "--csv" ||
                                                      a == "--plot" || a == "--label" || a == "--title")) {
            if (!value(a, v)) return false;
            auto &p = o.profile;
            if (a == "--channel") p.channel = v;
            else if (a == "--csv") p.csv = v;
            else if (a == "--plot") p.plot = v;
            else if (a == "--label") p.labels.push_back(v);
            else p.title = v;
        } else if (o.command == Command::Profile && (a == "--x0" || a == "--pitch" || a == "--diff-scale")) {
            if (!value(a, v)) return false;
            auto &p = o.profile;
            double d;
            if (!ParseDouble(v, d) || (a != "--x0" && !(d > 0))) {
                err = "'" + a + "' expects a " + (a == "--x0" ? "finite" : "positive") + " number" +
                      (a == "--diff-scale" ? "" : " (metres)") + "; got '" + v + "'";
                return false;
            }
            if (a == "--x0") { p.x0 = d; p.hasX0 = true; }
            else if (a == "--pitch") { p.pitch = d; p.hasPitch = true; }
            else p.diffScale = d;
        } else if (o.command == Command::Probe && (a == "--material" || a == "--theta" || a == "--phi" ||
                                                    a == "--lambda" || a == "--csv" || a == "--plot")) {
            if (!value(a, v)) return false;
            auto &p = o.probe;
            (a == "--material" ? p.material
             : a == "--theta"  ? p.theta
             : a == "--phi"    ? p.phi
             : a == "--lambda" ? p.lambda
             : a == "--csv"    ? p.csv
                               : p.plot) = v;
        } else if (o.command == Command::Probe && a == "--uv") {
            std::string us, vs;
            if (!value(a, us) || !value(a, vs)) {
                err = "'--uv' needs two numbers (U V)";
                return false;
            }
            if (!ParseDouble(us, o.probe.u) || !ParseDouble(vs, o.probe.v)) {
                err = "'--uv' expects two finite numbers; got '" + us + " " + vs + "'";
                return false;
            }
            o.probe.hasUv = true;
        } else if (o.command == Command::Probe && a == "--samples") {
            if (!value(a, v)) return false;
            if (!ParseInt(v, o.probe.samples) || o.probe.samples < 1) {
                err = "'--samples' expects a whole number ≥ 1; got '" + v + "'";
                return false;
            }
        } else if (o.command == Command::Probe && a == "--ray") o.probe.rayOptics = true;
        else if (a == "--quiet" || a == "-q") o.quiet = true;
        else if (a == "--strict") o.strict = true;
        else if (a == "--permissive") o.permissive = true;
        else if (a == "--markdown") o.markdown = true;
        else if (a == "--help" || a == "-h") { o.command = Command::Help; return true; }
        else if (!a.empty() && a[0] == '-') {
            err = "unknown option '" + a + "'";
            return false;
        } else positional.push_back(a);
    }
    if (o.strict && o.permissive) {
        err = "'--strict' (every warning is an error) and '--permissive' (unknown names are only warnings) "
              "contradict each other";
        return false;
    }
    switch (o.command) {
        case Command::Compare: {
            if (positional.size() != 1) {
                err = "'compare' expects exactly one scene file";
                return false;
            }
            o.scene = positional[0];
            const auto &c = o.compare;
            if (c.integrators.empty()) {
                err = "'compare' needs --integrators (e.g. --integrators grt,ray)";
                return false;
            }
            if (c.seconds > 0 && o.spp > 0) {
                err = "'--spp' (equal samples) and '--time' (equal time) exclude each other";
                return false;
            }
            if (!c.reference.empty() && !c.referenceIntegrator.empty()) {
                err = "'--reference' (an image) and '--reference-integrator' (a render) exclude each other";
                return false;
            }
            if (c.referenceSpp > 0 && c.referenceIntegrator.empty()) {
                err = "'--reference-spp' goes with '--reference-integrator'";
                return false;
            }
            break;
        }
        case Command::Render:
            if (!CheckRunOptions(o, err)) return false;
            if (!o.run.resume.empty() && positional.empty()) break;  // the scene is the checkpoint's
            [[fallthrough]];
        case Command::Check:
        case Command::Format:
            if (positional.size() != 1) {
                err = "'" + cmd + "' expects exactly one scene file";
                return false;
            }
            o.scene = positional[0];
            break;
        case Command::List:
            if (positional.size() > 1) { err = "'list' takes at most one family"; return false; }
            if (!positional.empty()) o.family = positional[0];
            break;
        case Command::Describe:
            if (o.markdown) break;
            // `describe NAME` finds a name unique across families; `describe FAMILY NAME` any.
            if (positional.size() == 1) {
                o.name = positional[0];
                break;
            }
            if (positional.size() != 2) { err = "'describe' expects [FAMILY] NAME"; return false; }
            o.family = positional[0];
            o.name = positional[1];
            break;
        case Command::Profile: {
            auto &p = o.profile;
            if (positional.empty()) { err = "'profile' expects at least one image file"; return false; }
            p.inputs = positional;
            if (!p.labels.empty() && p.labels.size() != p.inputs.size()) {
                err = "'profile' got " + std::to_string(p.labels.size()) + " --label for " +
                      std::to_string(p.inputs.size()) + " images (give one per image, in order)";
                return false;
            }
            if (p.hasX0 != p.hasPitch) { err = "'--x0' and '--pitch' go together"; return false; }
            if (p.hasX0 && p.column >= 0) {
                err = "'--x0' and '--pitch' give positions along a row; a column is indexed in pixels";
                return false;
            }
            break;
        }
        case Command::Probe: {
            const auto &p = o.probe;
            if (positional.size() != 1) { err = "'probe' expects exactly one scene file"; return false; }
            o.scene = positional[0];
            for (const auto &[flag, text] : {std::pair<const char *, const std::string &>{"--material", p.material},
                                             {"--theta", p.theta},
                                             {"--lambda", p.lambda}})
                if (text.empty()) { err = std::string("'probe' needs ") + flag; return false; }
            break;
        }
        default: break;
    }
    return true;
}

}  // namespace phasor

// SPDX-License-Identifier: Apache-2.0
// phasor — the command line through CLI11 (cli.h): the commands, their options and the usage text
// are declared once below; CLI11 parses argv and writes the help. Values are taken as text and
// checked here afterwards, so that every mistake reads the same way ("'--spp' expects a whole
// number ≥ 1; got '0'") and names what the option takes.

#include "app/cli.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <optional>

#include "core/diagnostics.h"
#include "core/plugin_families.h"

namespace phasor {

namespace {

// ---- values ------------------------------------------------------------------------------------

template <typename T>
bool ParseInt(const std::string &s, T &out) {
    auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    if (ec == std::errc() && p == s.data() + s.size()) return true;
    // A whole number written in scientific notation ("1e6" samples).
    char *end = nullptr;
    const double d = s.empty() || std::isspace(static_cast<unsigned char>(s[0])) ? NAN : std::strtod(s.c_str(), &end);
    if (!(end == s.c_str() + s.size() && std::isfinite(d) && d == std::floor(d) &&
          std::abs(d) < double(std::numeric_limits<T>::max())))
        return false;
    out = T(d);
    return true;
}
// A finite decimal number, the whole string.
bool ParseDouble(const std::string &s, double &out) {
    if (s.empty() || std::isspace(static_cast<unsigned char>(s[0]))) return false;
    char *end = nullptr;
    out = std::strtod(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}

// A mistake on the command line (the message ParseCommandLine returns).
struct Mistake {
    std::string message;
};

// A whole number option ≥ `min`: "'--spp' expects a whole number ≥ 1; got '0'".
template <typename T>
void WholeNumber(const std::string &flag, const std::optional<std::string> &text, T min, T &out) {
    if (!text) return;
    if (!ParseInt(*text, out) || out < min)
        throw Mistake{"'" + flag + "' expects a whole number ≥ " + std::to_string(min) + "; got '" + *text + "'"};
}

// ---- the commands ------------------------------------------------------------------------------

// "spectrum, texture, …": the plug-in families (core/plugin_families.h).
std::string Families() {
    std::string s;
#define PHASOR_FAMILY_NAME(Keyword, family, Interface, Example) s += (s.empty() ? "" : ", ") + std::string(#family);
    PHASOR_PLUGIN_FAMILIES(PHASOR_FAMILY_NAME)
#undef PHASOR_FAMILY_NAME
    return s;
}

const std::vector<std::pair<std::string, Command>> &CommandNames() {
    static const std::vector<std::pair<std::string, Command>> names = {
        {"render", Command::Render},     {"check", Command::Check},     {"format", Command::Format},
        {"list", Command::List},         {"describe", Command::Describe}, {"profile", Command::Profile},
        {"probe", Command::Probe},       {"compare", Command::Compare}};
    return names;
}

// What the parser fills before the values are checked: every value as the text written.
struct Raw {
    std::vector<std::string> positional;
    std::optional<std::string> spp, threads, seed, samples, time, referenceSpp, row, column, x0, pitch, diffScale;
    std::vector<std::string> defines, uv;
    std::optional<std::string> integrators;
    std::vector<std::string> sweeps;                 // render --sweep NAME=v1,v2,… (repeatable)
    std::optional<std::string> checkpoint, resume;  // render --checkpoint SECONDS, --resume FILE
};

// The declaration of every command and option: CLI11 parses with it and writes the help from it.
class Parser {
  public:
    Parser(CliOptions &o, Raw &raw) : app_("phasor: a wave-optical renderer (generalized rays)", "phasor") {
        app_.set_help_flag("-h,--help", "print this help (phasor COMMAND --help: one command's)");
        app_.add_flag("--version", version_, "print phasor's version");
        app_.require_subcommand(0, 1);
        app_.footer("Every scene file may be followed by -D name=value (override a Define), --strict (every "
                    "warning is an error) or --permissive (unknown names are warnings). Docs: README.md, docs/.");

        auto scene = [&](CLI::App *c, const char *what) {
            c->add_option("scene", raw.positional, what)->type_name("SCENE");
        };
        auto loading = [&](CLI::App *c) {
            c->add_option("-D", raw.defines, "override a Define of the scene: name=value (repeatable)")
                ->type_name("name=value")
                ->allow_extra_args(false);
            c->add_flag("--strict", o.strict, "every warning is an error");
            c->add_flag("--permissive", o.permissive, "unknown parameters and -D names that match no Define are warnings");
        };
        auto sampling = [&](CLI::App *c) {
            c->add_option("--spp", raw.spp, "samples per pixel (default: the scene's Render block)")->type_name("N");
            c->add_option("--seed", raw.seed, "random seed (default: the scene's)")->type_name("S");
            c->add_option("--threads", raw.threads, "threads (0: all cores)")->type_name("N");
            c->add_option("--sampler", o.sampler, "sobol (Owen-scrambled Sobol') or independent")->type_name("NAME");
        };
        auto quiet = [&](CLI::App *c) { c->add_flag("-q,--quiet", o.quiet, "no progress and no summary"); };

        CLI::App *render = Add("render", "render SCENE to FILE (.exr; a .png is written beside it)");
        scene(render, "the scene file (.wscene)");
        render->add_option("-o,--output", o.output, "the EXR to write (default: the scene's, else out/SCENE.exr)")
            ->type_name("FILE");
        render->add_option("--integrator", o.integrator, "an integrator the scene defines by name, or of that type")
            ->type_name("NAME");
        sampling(render);
        loading(render);
        quiet(render);
        // At scale (docs/distributed.md); under mpirun/srun the ranks share the work.
        render->add_option("--sweep", raw.sweeps, "one render per value of a Define (FILE-NAME=v.exr; repeatable: "
                                                  "every combination)")
            ->type_name("NAME=v1,v2,...")
            ->allow_extra_args(false);
        render->add_option("--checkpoint", raw.checkpoint, "write FILE.ckpt every SECONDS (resume with --resume)")
            ->type_name("SECONDS");
        render->add_option("--resume", raw.resume, "continue a checkpointed render bit for bit (SCENE optional)")
            ->type_name("FILE.ckpt");

        CLI::App *check = Add("check", "load and validate SCENE only, for the integrator render would use; exit "
                                       "status 0 if it is valid");
        scene(check, "the scene file (.wscene)");
        check->add_option("--integrator", o.integrator, "check for this integrator (as render --integrator)")
            ->type_name("NAME");
        loading(check);
        quiet(check);

        CLI::App *format = Add("format", "print SCENE in canonical form");
        scene(format, "the scene file (.wscene)");

        CLI::App *list = Add("list", "list the plug-ins of every family or of FAMILY (e.g. material, light)");
        list->add_option("family", raw.positional, "a family: " + Families())->type_name("FAMILY");

        CLI::App *describe = Add("describe", "print a plug-in's parameters (FAMILY only if NAME is in several)");
        describe->add_option("name", raw.positional, "[FAMILY] NAME, or Render for the Render block")
            ->type_name("[FAMILY] NAME");
        describe->add_flag("--markdown", o.markdown, "every plug-in's parameters as Markdown (docs/plugins.md)");

        CLI::App *profile =
            Add("profile", "one row (default: the middle one) or column of a channel of each image as CSV (stdout "
                           "unless --csv/--plot) and/or a line plot; with two images also |a - b|");
        profile->add_option("images", raw.positional, "EXR files")->type_name("IMAGE.exr ...");
        profile->add_option("--row", raw.row, "the row (default: each image's middle one)")->type_name("N");
        profile->add_option("--column", raw.column, "a column instead of a row")->type_name("N");
        profile->add_option("--channel", o.profile.channel, "the channel (default: intensity)")->type_name("NAME");
        profile->add_option("--csv", o.profile.csv, "write the CSV here (- for stdout)")->type_name("FILE|-");
        profile->add_option("--plot", o.profile.plot, "draw the plot here (.png, .svg, .pdf)")->type_name("FILE");
        profile->add_option("--label", o.profile.labels, "one label per image, in order (repeatable)")
            ->type_name("NAME")
            ->allow_extra_args(false);
        profile->add_option("--x0", raw.x0, "x of pixel 0's centre [m] (with --pitch)")->type_name("M");
        profile->add_option("--pitch", raw.pitch, "pixel pitch [m] (with --x0)")->type_name("M");
        profile->add_option("--diff-scale", raw.diffScale, "magnify |a - b| in the plot")->type_name("N");
        profile->add_option("--title", o.profile.title, "the plot's title")->type_name("TEXT");
        quiet(profile);

        CLI::App *probe = Add("probe", "one kernel of SCENE lit from (theta, phi) at wavelength lambda: R, T (power; "
                                       "continuous lobes by Monte Carlo), each near-delta lobe's direction and "
                                       "efficiency");
        scene(probe, "a scene file with the material (no light or detector needed)");
        probe->add_option("--material", o.probe.material, "the material's name")->type_name("NAME");
        probe->add_option("--theta", o.probe.theta, "incidence from the normal, e.g. 30deg")->type_name("ANGLE");
        probe->add_option("--phi", o.probe.phi, "azimuth from the kernel's reference direction (default 0)")
            ->type_name("ANGLE");
        probe->add_option("--lambda", o.probe.lambda, "vacuum wavelength, e.g. 550nm")->type_name("LENGTH");
        probe->add_option("--uv", raw.uv, "the texture coordinates (default 0.5 0.5)")->type_name("U V")->expected(2);
        probe->add_option("--samples", raw.samples, "Monte-Carlo samples of the continuous lobes (default 1e5)")
            ->type_name("N");
        probe->add_option("--seed", raw.seed, "random seed (default 0)")->type_name("S");
        probe->add_flag("--ray", o.probe.rayOptics, "the ray-optics limit");
        probe->add_option("--csv", o.probe.csv, "write the CSV here (- for stdout)")->type_name("FILE|-");
        probe->add_option("--plot", o.probe.plot, "draw the angular distribution here")->type_name("FILE");
        loading(probe);
        quiet(probe);

        CLI::App *compare = Add("compare", "render SCENE with each integrator (equal spp or equal time) and compare "
                                           "them: EXR/PNG each, grid, differences, table, plots, DIR/index.html");
        scene(compare, "the scene file (.wscene)");
        compare->add_option("--integrators", raw.integrators, "integrators to compare, or all")->type_name("A,B[,...]");
        compare->add_option("--time", raw.time, "equal time: seconds per integrator (instead of --spp)")
            ->type_name("SECONDS");
        compare->add_option("--reference", o.compare.reference, "compare against this image, or none")
            ->type_name("FILE.exr|none");
        compare->add_option("--reference-integrator", o.compare.referenceIntegrator,
                            "render this integrator as the reference (default: the first wave-optical one compared)")
            ->type_name("NAME");
        compare->add_option("--reference-spp", raw.referenceSpp, "the reference's samples per pixel in all "
                                                                 "(default: 4x the compared runs')")
            ->type_name("N");
        compare->add_option("--row", raw.row, "a profile plot along this row")->type_name("N");
        compare->add_option("--column", raw.column, "a profile plot along this column")->type_name("N");
        compare->add_option("-o,--output", o.output, "the output folder (default: out/SCENE_compare)")->type_name("DIR");
        sampling(compare);
        loading(compare);
        quiet(compare);
    }

    CLI::App &App() { return app_; }
    bool Version() const { return version_; }
    /// The command that was given (nullptr: none).
    CLI::App *Given() {
        for (CLI::App *c : app_.get_subcommands()) return c;
        return nullptr;
    }

  private:
    CLI::App *Add(const std::string &name, const std::string &description) {
        CLI::App *c = app_.add_subcommand(name, description);
        c->set_help_flag("-h,--help", "print this command's help");
        return c;
    }

    CLI::App app_;
    bool version_ = false;
};

// The first argument that CLI11 did not expect, from its message.
std::string Unexpected(const CLI::ExtrasError &e) {
    const std::string what = e.what();
    const std::size_t colon = what.find(": ");
    std::string rest = colon == std::string::npos ? what : what.substr(colon + 2);
    return rest.substr(0, rest.find(' '));
}

// --sweep NAME=v1,v2,…: commas inside (), [] or quotes belong to a value (rotate(90 deg, [1 0 0])).
void ParseSweep(const std::string &v, CliOptions::RunOptions &run) {
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
    if (name.empty() || std::any_of(values.begin(), values.end(), [](const std::string &x) { return x.empty(); }))
        throw Mistake{"'--sweep' expects NAME=value1,value2,… (a Define and its values); got '" + v + "'"};
    for (const auto &[n, vals] : run.sweeps)
        if (n == name) throw Mistake{"'--sweep' names '" + name + "' twice (give all its values in one --sweep)"};
    for (std::size_t i = 0; i < values.size(); ++i)
        if (std::find(values.begin(), values.begin() + std::ptrdiff_t(i), values[i]) != values.begin() + std::ptrdiff_t(i))
            throw Mistake{"'--sweep " + name + "' lists the value '" + values[i] + "' twice"};
    run.sweeps.emplace_back(name, std::move(values));
}

// render's options at scale (docs/distributed.md) and the combinations they allow.
void CheckRunOptions(CliOptions &o, const Raw &raw) {
    auto &run = o.run;
    for (const std::string &v : raw.sweeps) ParseSweep(v, run);
    if (raw.checkpoint && (!ParseDouble(*raw.checkpoint, run.checkpoint) || !(run.checkpoint > 0)))
        throw Mistake{"'--checkpoint' expects a positive number of seconds; got '" + *raw.checkpoint + "'"};
    if (raw.resume) run.resume = *raw.resume;
    if (!run.sweeps.empty() && (!run.resume.empty() || run.checkpoint > 0))
        throw Mistake{std::string("'--sweep' renders several images; '") +
                      (run.resume.empty() ? "--checkpoint" : "--resume") +
                      "' is for one render (render each value on its own to checkpoint it)"};
    for (const auto &[name, values] : run.sweeps)
        for (const auto &d : o.defines)
            if (d.first == name) throw Mistake{"'" + name + "' is given both by -D and by --sweep"};
}

// The checks of the values and of what goes together, after parsing.
void CheckValues(CliOptions &o, const Raw &raw, const std::string &cmd) {
    WholeNumber("--spp", raw.spp, 1, o.spp);
    WholeNumber("--threads", raw.threads, 0, o.threads);
    WholeNumber<long long>("--seed", raw.seed, 0, o.seed);
    if (o.strict && o.permissive)
        throw Mistake{"'--strict' (every warning is an error) and '--permissive' (unknown names are only warnings) "
                      "contradict each other"};
    for (const std::string &def : raw.defines) {
        const auto eq = def.find('=');
        if (eq == std::string::npos || eq == 0) throw Mistake{"'-D' expects name=value; got '" + def + "'"};
        o.defines.emplace_back(def.substr(0, eq), def.substr(eq + 1));
    }
    auto exactlyOneScene = [&] {
        if (raw.positional.size() != 1) throw Mistake{"'" + cmd + "' expects exactly one scene file"};
        o.scene = raw.positional[0];
    };
    int row = -1, column = -1;
    WholeNumber("--row", raw.row, 0, row);
    WholeNumber("--column", raw.column, 0, column);
    if (row >= 0 && column >= 0) throw Mistake{"'--row' and '--column' exclude each other (one profile per run)"};
    switch (o.command) {
        case Command::Render:
            CheckRunOptions(o, raw);
            if (!o.run.resume.empty() && raw.positional.empty()) break;  // the scene is the checkpoint's
            exactlyOneScene();
            break;
        case Command::Check:
        case Command::Format: exactlyOneScene(); break;
        case Command::List:
            if (raw.positional.size() > 1) throw Mistake{"'list' takes at most one family"};
            if (!raw.positional.empty()) o.family = raw.positional[0];
            break;
        case Command::Describe:
            if (o.markdown) break;
            // `describe NAME` finds a name unique across families; `describe FAMILY NAME` any.
            if (raw.positional.size() == 1) {
                o.name = raw.positional[0];
            } else if (raw.positional.size() == 2) {
                o.family = raw.positional[0];
                o.name = raw.positional[1];
            } else {
                throw Mistake{"'describe' expects [FAMILY] NAME"};
            }
            break;
        case Command::Profile: {
            auto &p = o.profile;
            if (raw.positional.empty()) throw Mistake{"'profile' expects at least one image file"};
            p.inputs = raw.positional;
            p.row = row;
            p.column = column;
            if (!p.labels.empty() && p.labels.size() != p.inputs.size())
                throw Mistake{"'profile' got " + std::to_string(p.labels.size()) + " --label for " +
                              std::to_string(p.inputs.size()) + " images (give one per image, in order)"};
            for (const auto &[flag, text, positive, value, has] :
                 {std::tuple<const char *, const std::optional<std::string> &, bool, double &, bool *>{
                      "--x0", raw.x0, false, p.x0, &p.hasX0},
                  {"--pitch", raw.pitch, true, p.pitch, &p.hasPitch},
                  {"--diff-scale", raw.diffScale, true, p.diffScale, nullptr}}) {
                if (!text) continue;
                if (!ParseDouble(*text, value) || (positive && !(value > 0)))
                    throw Mistake{std::string("'") + flag + "' expects a " + (positive ? "positive" : "finite") +
                                  " number" + (std::string(flag) == "--diff-scale" ? "" : " (metres)") + "; got '" +
                                  *text + "'"};
                if (has) *has = true;
            }
            if (p.hasX0 != p.hasPitch) throw Mistake{"'--x0' and '--pitch' go together"};
            if (p.hasX0 && p.column >= 0)
                throw Mistake{"'--x0' and '--pitch' give positions along a row; a column is indexed in pixels"};
            break;
        }
        case Command::Probe: {
            auto &p = o.probe;
            exactlyOneScene();
            if (!raw.uv.empty()) {
                if (raw.uv.size() != 2 || !ParseDouble(raw.uv[0], p.u) || !ParseDouble(raw.uv[1], p.v))
                    throw Mistake{"'--uv' expects two finite numbers; got '" + raw.uv[0] +
                                  (raw.uv.size() > 1 ? " " + raw.uv[1] : "") + "'"};
                p.hasUv = true;
            }
            WholeNumber<long long>("--samples", raw.samples, 1, p.samples);
            for (const auto &[flag, text] : {std::pair<const char *, const std::string &>{"--material", p.material},
                                             {"--theta", p.theta},
                                             {"--lambda", p.lambda}})
                if (text.empty()) throw Mistake{std::string("'probe' needs ") + flag};
            break;
        }
        case Command::Compare: {
            auto &c = o.compare;
            exactlyOneScene();
            c.row = row;
            c.column = column;
            if (!raw.integrators) throw Mistake{"'compare' needs --integrators (e.g. --integrators grt,ray)"};
            const std::string &v = *raw.integrators;
            for (std::size_t start = 0;;) {
                const std::size_t comma = v.find(',', start);
                const std::string name = v.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
                if (name.empty())
                    throw Mistake{"'--integrators' expects names separated by commas (e.g. grt,ray); got '" + v + "'"};
                if (std::find(c.integrators.begin(), c.integrators.end(), name) != c.integrators.end())
                    throw Mistake{"'--integrators' names '" + name + "' twice"};
                c.integrators.push_back(name);
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
            if (raw.time && (!ParseDouble(*raw.time, c.seconds) || !(c.seconds > 0)))
                throw Mistake{"'--time' expects a positive number of seconds; got '" + *raw.time + "'"};
            WholeNumber("--reference-spp", raw.referenceSpp, 1, c.referenceSpp);
            if (c.seconds > 0 && o.spp > 0)
                throw Mistake{"'--spp' (equal samples) and '--time' (equal time) exclude each other"};
            if (c.reference == "none" && c.referenceSpp > 0)
                throw Mistake{"'--reference none' renders no reference; '--reference-spp' has nothing to set"};
            if (!c.reference.empty() && !c.referenceIntegrator.empty())
                throw Mistake{"'--reference' (an image) and '--reference-integrator' (a render) exclude each other"};
            if (c.referenceSpp > 0 && !c.reference.empty())
                throw Mistake{"'--reference-spp' sets the samples of a rendered reference, not of '--reference' (an "
                              "image)"};
            break;
        }
        default: break;
    }
}

}  // namespace

bool ParseCommandLine(int argc, char **argv, CliOptions &o, std::string &err) {
    // Every mistake is one line that ends in where to read more.
    auto fail = [&](const std::string &message, const std::string &cmd) {
        err = message + " (see 'phasor " + (cmd.empty() ? "" : cmd + " ") + "--help')";
        return false;
    };
    if (argc < 2) return fail("no command given", "");
    // A mistyped command gets a suggestion (CLI11 would only call it unexpected).
    const std::string first = argv[1];
    if (!first.empty() && first[0] != '-') {
        std::vector<std::string> names = {"help"};
        for (const auto &[name, command] : CommandNames()) names.push_back(name);
        if (std::find(names.begin(), names.end(), first) == names.end()) {
            const std::string sug = Suggest(first, names);
            return fail("unknown command '" + first + "'" + (sug.empty() ? "" : "; did you mean '" + sug + "'?"), "");
        }
        if (first == "help") {
            o.command = Command::Help;
            o.helpFor = argc > 2 ? argv[2] : "";
            return true;
        }
    }
    Raw raw;
    Parser parser(o, raw);
    try {
        parser.App().parse(argc, argv);
    } catch (const CLI::CallForHelp &) {
        o.command = Command::Help;
        if (CLI::App *given = parser.Given()) o.helpFor = given->get_name();
        return true;
    } catch (const CLI::ParseError &e) {
        CLI::App *given = parser.Given();
        const std::string cmd = given ? given->get_name() : "";
        const std::string what = e.what();
        if (const auto *extras = dynamic_cast<const CLI::ExtrasError *>(&e)) {
            const std::string arg = Unexpected(*extras);
            if (!arg.empty() && arg[0] == '-') return fail("unknown option '" + arg + "'", cmd);
            if (given) return fail("'" + cmd + "' does not take '" + arg + "'", cmd);
            return fail("unexpected '" + arg + "'", cmd);
        }
        if (dynamic_cast<const CLI::ArgumentMismatch *>(&e)) {
            const std::string flag = what.substr(0, what.find(':'));
            return fail(flag == "--uv" ? std::string("'--uv' needs two numbers (U V)") : "'" + flag + "' needs a value",
                        cmd);
        }
        return fail(what, cmd);
    }
    if (parser.Version()) {
        o.command = Command::Version;
        return true;
    }
    CLI::App *given = parser.Given();
    if (!given) {
        o.command = Command::Help;
        return true;
    }
    const std::string cmd = given->get_name();
    for (const auto &[name, command] : CommandNames())
        if (name == cmd) o.command = command;
    try {
        CheckValues(o, raw, cmd);
    } catch (const Mistake &m) {
        return fail(m.message, cmd);
    }
    return true;
}

std::string UsageText(const std::string &command) {
    CliOptions o;
    Raw raw;
    Parser parser(o, raw);
    if (!command.empty())
        for (CLI::App *c : parser.App().get_subcommands({}))
            if (c->get_name() == command) return c->help();
    return parser.App().help();
}

}  // namespace phasor

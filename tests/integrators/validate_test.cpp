// SPDX-License-Identifier: Apache-2.0
// Scene checks at load (issue 25 §3, issue 26 §2): every integrator's refusal comes from
// Scene::Build (Integrator::Validate, from the declarations of Integrator::Support), located at
// the object at fault, so `phasor check` says what `render` would; a light an integrator cannot
// reach in the scene is a warning at load, and the black-image message then gives advice that
// fits the integrator. rs's own refusals are in rs_test.cpp (RsScene.*LoadErrors*).
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "core/render/integrator.h"
#include "parser/parser.h"
#include "support/scene_builder.h"

namespace phasor::test {
namespace {

// A detector that generates classical rays only (no generalized rays): what grt and sample_solve
// must refuse at load. Registered in this test executable only.
class RaysOnlyDetector final : public Detector {
  public:
    RaysOnlyDetector() : Detector(2, 2, SensorResponse(SensorResponse::Kind::Radiometric)) {}
    static const Schema &GetSchema() {
        static const Schema s{"detector", "test_rays_only", "test detector: classical rays only", {}};
        return s;
    }
    static std::unique_ptr<Detector> Create(const ParamDict &, BuildContext &) {
        return std::make_unique<RaysOnlyDetector>();
    }
    std::optional<DetectorSample> Generate(const Vec2 &p, const Vec2 &) const override {
        return DetectorSample{Ray{Vec3(p.x, p.y, 1), Vec3(0, 0, -1)}, 1};
    }
    std::string ToString() const override { return "test_rays_only"; }
};
PHASOR_REGISTER_PLUGIN(Detector, RaysOnlyDetector, "test_rays_only");

struct Loaded {
    std::unique_ptr<Scene> scene;
    std::string log;
};

Loaded Load(const std::string &text, const std::string &integrator = "") {
    Diagnostics diag;
    Loaded out;
    auto desc = ParseSceneString(text, "validate.wscene", DefineList{}, diag);
    if (desc) out.scene = Scene::Build(*desc, diag, integrator);
    std::ostringstream os;
    diag.Print(os);
    out.log = os.str();
    return out;
}

// A diffuse floor under a small lamp, seen by a camera (line 6) or a test detector (line 7).
const char *const kRoom = R"(wscene 2
Material "diffuse" "white" { reflectance = 0.5 }
Shape "rectangle" "floor" { material = @white }
Shape "disk" "lamp" { radius = 0.1 m  to_world = [rotate(180 deg, [1 0 0]) translate([0 0 1] m)] }
Light "area" "glow" { shape = @lamp }
Detector "perspective" "cam" { to_world = lookat([0 0 3] m, [0 0 0] m, [0 1 0])  resolution = [4 4] }
Detector "test_rays_only" "plain" {}
Render { detector = @DET }
)";

std::string Room(const std::string &detector) {
    std::string s = kRoom;
    s.replace(s.find("@DET"), 4, "@" + detector);
    return s;
}

TEST(Validate, GeneralizedRayIntegratorsRefuseAClassicalDetectorAtLoad) {
    for (const char *integrator : {"grt", "sample_solve"}) {
        const Loaded l = Load(Room("plain"), integrator);
        EXPECT_FALSE(l.scene) << integrator;
        EXPECT_NE(l.log.find("validate.wscene:7:1: error: integrator '" + std::string(integrator) +
                             "' needs a detector that generates generalized rays"),
                  std::string::npos)
            << l.log;
    }
    EXPECT_TRUE(Load(Room("plain"), "ray").scene);  // ray takes any detector
    EXPECT_TRUE(Load(Room("cam"), "grt").scene);
}

TEST(Validate, PolarisationNeedsAnIntegratorThatCarriesIt) {
    std::string text = Room("cam");
    text.replace(text.find("resolution = [4 4]"), 18, "resolution = [4 4]  polarizer = 30 deg");
    for (const char *integrator : {"grt", "ray"}) {
        const Loaded l = Load(text, integrator);
        EXPECT_FALSE(l.scene);
        EXPECT_NE(l.log.find("validate.wscene:6:"), std::string::npos) << l.log;
        EXPECT_NE(l.log.find("error: detector 'cam' asks for a polarizer, but integrator '" + std::string(integrator) +
                             "' carries no polarisation"),
                  std::string::npos)
            << l.log;
    }
    EXPECT_TRUE(Load(text, "sample_solve").scene);
}

TEST(Validate, TheDefaultIntegratorIsTheOneThatDeclaresItself) {
    const Loaded l = Load(Room("cam"));
    ASSERT_TRUE(l.scene) << l.log;
    EXPECT_EQ(l.scene->GetIntegrator().name, "ray");
    ASSERT_TRUE(Registry<Integrator>::Default());
    EXPECT_STREQ(Registry<Integrator>::Default()->name, "ray");
    int defaults = 0;
    for (const auto &e : Registry<Integrator>::Entries()) defaults += e.isDefault();
    EXPECT_EQ(defaults, 1);
}

// issue 26 §2: a laser or plane wave seen on a virtual_plane only through a mirror. `ray` cannot
// reach it (a delta light after a specular bounce): a warning at load names the light and the fix,
// and the black image's cause says the same — not "turn the light or the sensor", which would
// break the grt render. grt reads the reflected wave.
TEST(Validate, RayCannotReachADeltaLightThroughAMirror) {
    const std::string file = std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/screen_behind_mirror.wscene";
    for (const char *source : {"\"plane\"", "\"point\""}) {
        Diagnostics diag;
        ParseOptions opt;
        opt.defines = {{"source", source}};
        auto desc = ParseSceneFile(file, opt, diag);
        ASSERT_TRUE(desc);
        auto ray = Scene::Build(*desc, diag, "ray");
        ASSERT_TRUE(ray);
        std::ostringstream os;
        diag.Print(os);
        EXPECT_NE(os.str().find("warning: integrator 'ray' cannot reach light '"), std::string::npos) << os.str();
        EXPECT_NE(os.str().find("use integrator \"grt\""), std::string::npos) << os.str();
        const Image img = RenderImage(*ray, 1);
        EXPECT_TRUE(std::all_of(img.data.begin(), img.data.end(), [](float v) { return v == 0; }));
        const std::string cause = ray->DarkImageCause();
        EXPECT_NE(cause.find("integrator 'ray' cannot reach light"), std::string::npos) << cause;
        EXPECT_EQ(cause.find("turn the light"), std::string::npos) << cause;

        Diagnostics quiet;
        auto grt = Scene::Build(*desc, quiet, "grt");
        ASSERT_TRUE(grt);
        EXPECT_EQ(quiet.WarningCount(), 0u);
        const Image lit = RenderImage(*grt, 1);
        EXPECT_GT(*std::max_element(lit.data.begin(), lit.data.end()), 0.1f);
    }
}

// With a diffuse surface in the scene the delta light is reachable in principle: no warning at
// load. If the image is black all the same, the cause names the integrator's limit, not the light's
// direction (the sensor sees only the mirror).
TEST(Validate, ABlackRayImageWithADiffuseSurfaceElsewhereBlamesTheIntegrator) {
    const std::string file = std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/screen_behind_mirror.wscene";
    Diagnostics diag;
    auto desc = ParseSceneFile(file, ParseOptions{}, diag);
    ASSERT_TRUE(desc);
    SceneEntity matte;
    matte.keyword = "Material";
    matte.type = "diffuse";
    matte.name = "matte";
    desc->entities.insert(desc->entities.begin(), matte);
    SceneEntity wall;
    wall.keyword = "Shape";
    wall.type = "rectangle";
    wall.name = "wall";
    wall.params.Set("material", Value::Ref("matte"));
    wall.params.Set("to_world", Value::Call("translate", {Value::Vector({0, 0, -1}, Dim::Length())}, {""}));
    desc->entities.push_back(wall);
    auto ray = Scene::Build(*desc, diag, "ray");
    ASSERT_TRUE(ray);
    EXPECT_EQ(diag.WarningCount(), 0u);
    const std::string cause = ray->DarkImageCause();
    EXPECT_NE(cause.find("integrator 'ray' reaches the delta light 'wave' only by next-event estimation"),
              std::string::npos)
        << cause;
}

// The double slit's plane wave on the sensor through the plate: ray cannot see it either (the
// aperture is a straight delta transmission in ray optics).
TEST(Validate, RayCannotReachAPlaneWaveThroughAnAperture) {
    const std::string file = std::string(PHASOR_SOURCE_DIR) + "/scenes/validation/double_slit.wscene";
    Diagnostics diag;
    auto desc = ParseSceneFile(file, ParseOptions{}, diag);
    ASSERT_TRUE(desc);
    ASSERT_TRUE(Scene::Build(*desc, diag, "ray"));
    std::ostringstream os;
    diag.Print(os);
    EXPECT_NE(os.str().find("warning: integrator 'ray' cannot reach light 'wave'"), std::string::npos) << os.str();
}

// Every integrator declares its support, and the declarations are consistent with its contract
// cases: an integrator that declares a sensor-plane case measures delta lights.
TEST(Validate, EveryIntegratorDeclaresWhatItRenders) {
    const std::string table = SupportMarkdown();
    EXPECT_EQ(table.find("not built with its default parameters"), std::string::npos) << table;
    for (const auto &e : Registry<Integrator>::Entries()) {
        EXPECT_NE(table.find("`" + std::string(e.name) + "`"), std::string::npos) << e.name;
        Diagnostics diag;
        SceneDesc desc;
        BuildContext ctx(desc, diag);
        ParamDict d;
        d.Validate(e.schema(), diag);
        const std::unique_ptr<Integrator> integrator = e.create(d, ctx);
        const IntegratorSupport s = integrator->Support();
        const auto cases = e.contractCases().value_or(std::vector<std::string>{});
        const bool sensorCase = std::find(cases.begin(), cases.end(), "plane_wave_sensor") != cases.end();
        if (sensorCase) {
            EXPECT_EQ(s.Reach(LightType::DeltaDirection), LightReach::ClosedForm) << e.name;
            EXPECT_EQ(s.Reach(LightType::DeltaPosition), LightReach::ClosedForm) << e.name;
        }
    }
}

// Samplers are a plug-in family: Render.sampler names a plug-in or a Sampler block, checked at load
// with a suggestion; the default is the plug-in that declares itself so (sobol).
TEST(Validate, SamplersAreChosenByNameAtLoad) {
    auto with = [](const std::string &extra) {
        std::string s = Room("cam");
        s.replace(s.find("Render { detector = @cam }"), 26, extra);
        return s;
    };
    const Loaded plain = Load(with("Render { detector = @cam }"));
    ASSERT_TRUE(plain.scene) << plain.log;
    EXPECT_EQ(plain.scene->Settings().options.sampler, "sobol");
    const Loaded chosen = Load(with("Render { detector = @cam  sampler = \"independent\" }"));
    ASSERT_TRUE(chosen.scene) << chosen.log;
    EXPECT_EQ(chosen.scene->NewSampler(chosen.scene->Settings().options.sampler, 3)->Name(), "independent");
    const Loaded block = Load(with("Sampler \"independent\" \"mine\" {}\nRender { detector = @cam }"));
    ASSERT_TRUE(block.scene) << block.log;
    EXPECT_EQ(block.scene->Settings().options.sampler, "mine");
    EXPECT_EQ(block.scene->NewSampler("mine", 3)->Name(), "independent");
    EXPECT_EQ(block.scene->NewSampler("mine", 3)->Seed(), 3u);
    const Loaded typo = Load(with("Render { detector = @cam  sampler = \"sobl\" }"));
    EXPECT_FALSE(typo.scene);
    EXPECT_NE(typo.log.find("validate.wscene:8:37: error: unknown sampler 'sobl'; did you mean 'sobol'?"),
              std::string::npos)
        << typo.log;
}

}  // namespace
}  // namespace phasor::test

// SPDX-License-Identifier: Apache-2.0
// phasor's Python module: phasor.Image — a rendered (or read) image as numpy views without copies,
// its metadata, and the program's own writers and display transforms (core/image/image_io.h,
// app/render_common.h StageDisplayPng).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image/image_io.h"
#include "core/image/output_file.h"
#include "python/common.h"

namespace phasor::python {

namespace {

namespace fs = std::filesystem;

bool Radiometric(const Image &img) {
    auto it = img.metadata.find("phasor:sensor");
    return it != img.metadata.end() && it->second == "radiometric";
}

// A read-only numpy view of `img`'s float data (kept alive by `owner`): all channels (H×W×C) or
// channel c (H×W, strided).
py::array View(const py::object &owner, const Image &img, int c) {
    const std::size_t nc = img.channels.size(), f = sizeof(float);
    py::array a;
    if (c < 0)
        a = py::array_t<float>({std::size_t(img.height), std::size_t(img.width), nc},
                               {img.width * nc * f, nc * f, f}, img.data.data(), owner);
    else
        a = py::array_t<float>({std::size_t(img.height), std::size_t(img.width)}, {img.width * nc * f, nc * f},
                               img.data.data() + c, owner);
    a.attr("setflags")(py::arg("write") = false);
    return a;
}

py::array_t<uint8_t> ToArray(Rgb8Image rgb) {
    py::array_t<uint8_t> a({std::size_t(rgb.height), std::size_t(rgb.width), std::size_t(3)});
    std::copy(rgb.rgb.begin(), rgb.rgb.end(), a.mutable_data());
    return a;
}

// The label and title the program gives the display PNG of a render.
std::string Label(const PyImage &p) {
    auto it = p.image.metadata.find("phasor:integrator");
    if (!p.integrator.empty()) return p.integrator;
    return it != p.image.metadata.end() ? it->second.substr(0, it->second.find(' ')) : std::string("image");
}
std::string Title(const PyImage &p) {
    auto it = p.image.metadata.find("phasor:scene");
    const std::string scene = it != p.image.metadata.end() ? fs::path(it->second).filename().string() : "image";
    return scene + ": intensity";
}

// The display exposure [stops] `phasor render` gave the image's PNG (phasor:display_exposure; 0
// for an image without it).
double DisplayExposure(const Image &img) {
    const auto it = img.metadata.find("phasor:display_exposure");
    if (it == img.metadata.end()) return 0;
    try {
        return std::stod(it->second);
    } catch (const std::exception &) {
        return 0;
    }
}

// Writes the PNG `phasor render` writes beside its EXR (StageDisplayPng); returns the file written
// (a CSV instead of a one-row image's plot when matplotlib is missing, with a warning).
std::string WriteDisplayPng(const PyImage &p, const std::string &path) {
    std::string shown;
    {
        py::gil_scoped_release release;
        MakeParentDirectory(path);
        OutputFiles files;
        shown = StageDisplayPng(files, path, p.image, Radiometric(p.image), Label(p), Title(p), 0,
                                DisplayExposure(p.image));
        files.Commit();
    }
    if (shown != path) EmitRenderWarning("'" + path + "' not drawn (matplotlib is missing); its data is in '" + shown + "'");
    return shown;
}

}  // namespace

void BindImage(py::module_ &m) {
    py::class_<PyImage, std::shared_ptr<PyImage>> image(m, "Image", R"doc(
An image rendered by phasor (Scene.render) or read from a file (phasor.read_image): named float32
channels (R G B intensity variance, and S0..S3 DoP with Stokes output, `samples` after a stopped
render), row-major with the top row first, and the metadata the EXR records.

image["intensity"] is an H x W numpy float32 view of one channel, without a copy (its strides step
over the other channels); image.array is the H x W x C view; both are read-only and keep the image
alive. A rendered image also keeps its scene alive (image.scene).)doc");
    image
        .def_property_readonly("width", [](const PyImage &p) { return p.image.width; }, "Width in pixels.")
        .def_property_readonly("height", [](const PyImage &p) { return p.image.height; }, "Height in pixels.")
        .def_property_readonly("shape", [](const PyImage &p) { return py::make_tuple(p.image.height, p.image.width); },
                               "(height, width).")
        .def_property_readonly("channels", [](const PyImage &p) { return p.image.channels; },
                               "The channel names, in the EXR's order.")
        .def_property_readonly(
            "metadata",
            [](const PyImage &p) {
                py::dict d;
                for (const auto &[k, v] : p.image.metadata) d[py::str(k)] = v;
                return d;
            },
            "The metadata the EXR records (a copy): phasor:spp_requested, phasor:spp_reached, phasor:seed, "
            "phasor:sampler, phasor:integrator, phasor:render_seconds, phasor:cancelled, ... (strings, as in "
            "the file).")
        .def_property_readonly(
            "scene", [](const PyImage &p) -> py::object { return p.scene ? py::cast(p.scene) : py::object(py::none()); },
            "The Scene rendered (None for an image read from a file).")
        .def_property_readonly("warnings", [](const PyImage &p) { return p.warnings; },
                               "The render's warnings (also given through Python's warnings module).")
        .def_property_readonly(
            "radiometric", [](const PyImage &p) { return Radiometric(p.image); },
            "True for a detector with a radiometric response (its PNG is false colour in dB), False for a camera's RGB.")
        .def_property_readonly(
            "array", [](const py::object &self) { return View(self, self.cast<const PyImage &>().image, -1); },
            "All channels as an H x W x C read-only float32 view (no copy).")
        .def(
            "__array__",
            [](const py::object &self, const py::object &dtype) {
                py::array a = View(self, self.cast<const PyImage &>().image, -1);
                return dtype.is_none() ? a : py::array(a.attr("astype")(dtype));
            },
            py::arg("dtype") = py::none(), "numpy.asarray(image): the H x W x C channels.")
        .def(
            "__getitem__",
            [](const py::object &self, const std::string &name) {
                const Image &img = self.cast<const PyImage &>().image;
                const int c = img.ChannelIndex(name);
                if (c < 0) {
                    std::string names;
                    for (const std::string &n : img.channels) names += (names.empty() ? "" : ", ") + n;
                    throw py::key_error("no channel '" + name + "' (channels: " + names + ")");
                }
                return View(self, img, c);
            },
            py::arg("channel"), "image[\"intensity\"]: one channel as an H x W read-only float32 view (no copy).")
        .def("__contains__", [](const PyImage &p, const std::string &name) { return p.image.ChannelIndex(name) >= 0; })
        .def(
            "write",
            [](const PyImage &p, const py::object &pathObject) {
                const std::string path = py::str(py::module_::import("os").attr("fspath")(pathObject));
                const std::string ext = fs::path(path).extension().string();
                try {
                    if (ext == ".exr") {
                        py::gil_scoped_release release;
                        MakeParentDirectory(path);
                        WriteExr(path, p.image);
                        return path;
                    }
                    if (ext == ".png") return WriteDisplayPng(p, path);
                } catch (const Error &e) {
                    RaisePhasorError(e);
                }
                throw py::value_error("'" + path + "': write() writes .exr (every channel and the metadata) or .png "
                                      "(the display image phasor render writes)");
            },
            py::arg("path"), R"doc(
Writes the image: FILE.exr as `phasor render` writes it (every channel, float, and the metadata),
or FILE.png as the PNG it writes beside the EXR (a camera's through the OpenColorIO display
transform, a radiometric detector's in false-colour dB with a colour bar, a one-row image as a line
plot). All or nothing, as the program's outputs. Returns the path written.)doc")
        .def(
            "to_srgb",
            [](const PyImage &p, std::optional<double> exposure) {
                try {
                    if (Radiometric(p.image)) return ToArray(ToFalseColourDb(p.image, "intensity", 40, 0));
                    DisplayOptions opt;
                    opt.exposure = exposure.value_or(DisplayExposure(p.image));
                    return ToArray(ToDisplay(p.image, opt));
                } catch (const Error &e) {
                    RaisePhasorError(e);
                }
            },
            py::arg("exposure") = py::none(), R"doc(
The display image as an H x W x 3 uint8 array (sRGB): a camera's R, G, B through the OpenColorIO
display transform of `phasor render`'s PNG (sRGB, view Standard; `exposure` in stops, None: the
image's phasor:display_exposure as its PNG, the detector's `exposure`/auto-exposure), a
radiometric detector's intensity in false-colour dB (viridis, 0 dB = the maximum, 40 dB shown)
as in its PNG (without the colour bar).)doc")
        .def(
            "_repr_png_",
            [](const PyImage &p) {
                // The PNG the program writes, through a temporary file (its writer stages files).
                std::string tmpl = (fs::temp_directory_path() / "phasor-png-XXXXXX").string();
                if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a temporary directory");
                const std::string dir = tmpl;
                const fs::path png = fs::path(dir) / "image.png";
                std::string bytes;
                try {
                    const std::string shown = WriteDisplayPng(p, png.string());
                    std::ifstream in(shown, std::ios::binary);
                    std::ostringstream os;
                    os << in.rdbuf();
                    bytes = os.str();
                } catch (...) {
                    std::error_code ec;
                    fs::remove_all(dir, ec);
                    throw;
                }
                std::error_code ec;
                fs::remove_all(dir, ec);
                if (bytes.size() < 8 || bytes.compare(1, 3, "PNG") != 0) return py::object(py::none());
                return py::object(py::bytes(bytes));
            },
            "The PNG phasor render writes beside its EXR, as bytes: Jupyter shows an Image by it.")
        .def("__repr__", [](const PyImage &p) {
            std::string channels;
            for (const std::string &n : p.image.channels) channels += (channels.empty() ? "" : " ") + n;
            auto get = [&](const char *k) {
                auto it = p.image.metadata.find(k);
                return it == p.image.metadata.end() ? std::string() : it->second;
            };
            std::string s = "<phasor.Image " + std::to_string(p.image.width) + "x" + std::to_string(p.image.height) +
                            " [" + channels + "]";
            if (!get("phasor:integrator").empty()) s += " " + get("phasor:integrator").substr(0, get("phasor:integrator").find(' '));
            if (!get("phasor:spp_reached").empty()) s += ", " + get("phasor:spp_reached") + " spp";
            if (get("phasor:cancelled") == "true") s += ", cancelled";
            return s + ">";
        });

    m.def(
        "read_image",
        [](const py::object &pathObject) {
            const std::string path = py::str(py::module_::import("os").attr("fspath")(pathObject));
            auto p = std::make_shared<PyImage>();
            try {
                py::gil_scoped_release release;
                p->image = ReadImage(path);
            } catch (const Error &e) {
                RaisePhasorError(e);
            }
            return p;
        },
        py::arg("path"), R"doc(
Reads an image file (an EXR phasor wrote, or anything OpenImageIO reads) -> Image, with its
channels and metadata; integer formats are normalised to [0, 1] and not decoded.)doc");
}

}  // namespace phasor::python

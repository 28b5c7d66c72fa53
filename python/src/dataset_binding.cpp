#include "dataset_binding.hpp"

#include <pybind11/stl.h>

#include <filesystem>
#include <memory>
#include <mutex>

#include "arrays.hpp"
#include "camera_binding.hpp"
#include "libcam/error.hpp"
#include "libcam/dataset/colmap_dataset.hpp"
#include "libcam/dataset/dataset_tasks.hpp"

namespace libcam::python {

namespace {

namespace fs = std::filesystem;

// The options `libcam dataset` takes, from the Python call's. Paths are made absolute, so
// that the tasks name the same files from any working folder.
DatasetOptions dataset_options(const std::string& source, const std::string& output, const std::optional<std::string>& images,
                               const std::string& camera, const py::object& size, const std::string& to, bool masks,
                               const std::string& interpolation, int jpeg_quality, bool text, int threads) {
    DatasetOptions options;
    options.model = source;
    options.output = fs::absolute(output);
    set_dataset_camera(options, camera, size.is_none() ? std::nullopt : std::optional<ImageSize>(size_from(size)));
    if (to == "nerf") {
        options.to = DatasetFormat::Nerf;
        if (text) throw InvalidArgument("text: not with to='nerf' (transforms.json is text)");
    } else if (to != "colmap") {
        throw InvalidArgument("to: expected 'colmap' or 'nerf', got '" + to + "'");
    }
    options.masks = masks;
    options.text = text;
    options.interpolation = interpolation_from_string(interpolation);
    if (jpeg_quality < 1 || jpeg_quality > 100) {
        throw InvalidArgument("jpeg_quality: expected 1 to 100, got " + std::to_string(jpeg_quality));
    }
    options.jpeg_quality = jpeg_quality;
    options.threads = thread_count(threads);
    options.images = fs::absolute(images ? fs::path(*images) : default_dataset_images(options.model));
    std::error_code error;
    if (!fs::is_directory(options.images, error)) {
        throw FileError(options.images.string() + ": no such images folder (give images=...)");
    }
    return options;
}

py::dict summary_dict(const DatasetSummary& summary) {
    return py::module_::import("json").attr("loads")(dataset_summary_json(summary)).cast<py::dict>();
}

// The maps this process keeps for the tasks it runs: one cache for every task, whichever
// plan it came from. Never destroyed: the interpreter may end before OpenCV's own
// statics, and the maps are memory the process gives back when it ends anyway.
struct ProcessMaps {
    std::mutex lock;
    std::shared_ptr<MapCache> cache = std::make_shared<MapCache>();
};

ProcessMaps& process_maps() {
    static ProcessMaps* const maps = new ProcessMaps;
    return *maps;
}

std::shared_ptr<MapCache> current_maps() {
    ProcessMaps& maps = process_maps();
    const std::lock_guard<std::mutex> lock(maps.lock);
    return maps.cache;
}

py::dict map_cache(const std::optional<std::size_t>& capacity, const std::optional<int>& threads) {
    ProcessMaps& maps = process_maps();
    const std::lock_guard<std::mutex> lock(maps.lock);
    if (capacity || threads) {
        if (capacity && *capacity < 1) throw InvalidArgument("capacity: expected 1 or more maps, got 0");
        maps.cache = std::make_shared<MapCache>(capacity.value_or(maps.cache->capacity()),
                                                threads ? thread_count(*threads) : maps.cache->threads());
    }
    py::dict out;
    out["capacity"] = maps.cache->capacity();
    out["threads"] = maps.cache->threads();
    out["maps"] = maps.cache->size();
    out["builds"] = maps.cache->builds();
    return out;
}

// A plan as Python holds it: the tasks made into Python objects once, not at every access,
// and what finish_dataset needs (the plan without its tasks).
struct PythonPlan {
    py::list tasks;
    py::dict summary;
    DatasetPlan plan;
};

py::object optional_path(const fs::path& path) { return path.empty() ? py::object(py::none()) : py::str(path.string()); }

}  // namespace

void bind_dataset(py::module_& m) {
    py::class_<ImageTask>(m, "ImageTask", R"doc(
One output image of a dataset plan: everything needed to make it (both cameras, the view's
turn, the interpolation, the JPEG quality, the paths), so it runs in any process that sees
the same files. Picklable (its state is one line of JSON: to_json()), so Dask,
multiprocessing or a queue of one's own can send it to another process or machine.)doc")
        .def(
            "run",
            [](const ImageTask& task) {
                const std::shared_ptr<MapCache> maps = current_maps();
                py::gil_scoped_release release;
                run_image_task(task, *maps);
            },
            R"doc(
Reads the source image, remaps it through its camera's map (built on first use and kept in
this process's map cache: libcam.dataset.map_cache) or copies it, and writes it and its
mask, each to a temporary name renamed into place. Releases the GIL. Raises
libcam.FileError naming the image for one that cannot be read or written.)doc")
        .def("to_json", &image_task_json, "The task as one line of JSON (every number to the last bit).")
        .def_static(
            "from_json", [](const std::string& text) { return image_task_from_json(text); }, py::arg("text"),
            "The task a to_json() line holds; libcam.FileError naming the field for text that is not one.")
        .def_property_readonly("source_path", [](const ImageTask& t) { return t.source_path.string(); })
        .def_property_readonly("target_path", [](const ImageTask& t) { return t.target_path.string(); })
        .def_property_readonly("mask_path", [](const ImageTask& t) { return optional_path(t.mask_path); },
                               "The mask written beside the image, or None.")
        .def_property_readonly("source", [](const ImageTask& t) { return PythonCamera(t.source); },
                               "The source image's camera (its lens).")
        .def_property_readonly("camera", [](const ImageTask& t) { return PythonCamera(t.camera); },
                               "The new pinhole the image is remapped into.")
        .def_property_readonly("turn", [](const ImageTask& t) { return to_numpy(t.turn); },
                               "The new camera's axes relative to the source's (a view's turn; else the identity).")
        .def_property_readonly("copy", [](const ImageTask& t) { return t.copy; },
                               "True when the source camera is kept as it was and the file is copied byte for byte.")
        .def_property_readonly("interpolation", [](const ImageTask& t) { return std::string(to_string(t.interpolation)); })
        .def_property_readonly("jpeg_quality", [](const ImageTask& t) { return t.jpeg_quality; })
        .def("__repr__",
             [](const ImageTask& t) { return "<libcam ImageTask " + t.source_path.string() + " -> " + t.target_path.string() + ">"; })
        .def(py::pickle([](const ImageTask& t) { return py::make_tuple(image_task_json(t)); },
                        [](const py::tuple& state) {
                            if (state.size() != 1) throw InvalidArgument("ImageTask: expected a pickled state of one JSON line");
                            return image_task_from_json(state[0].cast<std::string>(), "pickled image task");
                        }));

    py::class_<PythonPlan>(m, "DatasetPlan", R"doc(
What libcam.dataset.plan did and what is left: tasks (one libcam.dataset.ImageTask per
output image not already made, in camera order) and summary (the dict `libcam dataset
--json` prints, images_kept counting the images already made, images_written 0, finished
False). libcam.dataset.finish(plan) moves the whole into place once every task has run.)doc")
        .def_readonly("tasks", &PythonPlan::tasks)
        .def_readonly("summary", &PythonPlan::summary)
        .def("__repr__", [](const PythonPlan& plan) {
            return "<libcam DatasetPlan: " + std::to_string(plan.tasks.size()) + " image tasks, model " +
                   plan.summary["model"].cast<std::string>() + ">";
        });

    m.def(
        "dataset_plan",
        [](const std::string& source, const std::string& output, const std::optional<std::string>& images,
           const std::string& camera, const py::object& size, const std::string& to, bool masks,
           const std::string& interpolation, int jpeg_quality, bool text, int threads) {
            const DatasetOptions options = dataset_options(source, output, images, camera, size, to, masks, interpolation,
                                                           jpeg_quality, text, threads);
            DatasetPlan plan;
            {
                py::gil_scoped_release release;
                plan = plan_dataset(options);
            }
            PythonPlan out;
            for (ImageTask& task : plan.tasks) out.tasks.append(py::cast(std::move(task)));
            plan.tasks.clear();
            out.summary = summary_dict(plan.summary);
            out.plan = std::move(plan);
            return out;
        },
        py::arg("src"), py::arg("output"), py::arg("images") = py::none(), py::arg("camera") = "valid",
        py::arg("size") = py::none(), py::arg("to") = "colmap", py::arg("masks") = false,
        py::arg("interpolation") = "cubic", py::arg("jpeg_quality") = kDefaultJpegQuality, py::arg("text") = false,
        py::arg("threads") = 0, "libcam.dataset.plan (the docstring is there).");

    m.def(
        "dataset_run",
        [](const std::string& source, const std::string& output, const std::optional<std::string>& images,
           const std::string& camera, const py::object& size, const std::string& to, bool masks,
           const std::string& interpolation, int jpeg_quality, bool text, int threads) {
            DatasetOptions options = dataset_options(source, output, images, camera, size, to, masks, interpolation,
                                                     jpeg_quality, text, threads);
            std::vector<std::string> errors;
            options.on_image_error = [&errors](const std::string& line) { errors.push_back(line); };
            DatasetSummary summary;
            {
                py::gil_scoped_release release;
                summary = make_pinhole_dataset(options);
            }
            py::dict out = summary_dict(summary);
            out["errors"] = errors;
            return out;
        },
        py::arg("src"), py::arg("output"), py::arg("images") = py::none(), py::arg("camera") = "valid",
        py::arg("size") = py::none(), py::arg("to") = "colmap", py::arg("masks") = false,
        py::arg("interpolation") = "cubic", py::arg("jpeg_quality") = kDefaultJpegQuality, py::arg("text") = false,
        py::arg("threads") = 0, "libcam.dataset.run (the docstring is there).");

    m.def(
        "dataset_finish",
        [](PythonPlan& plan) {
            DatasetSummary summary;
            {
                py::gil_scoped_release release;
                summary = finish_dataset(plan.plan);
            }
            plan.plan.lock.reset();  // finished: the output folder is free for another run
            return summary_dict(summary);
        },
        py::arg("plan"), "libcam.dataset.finish (the docstring is there).");

    m.def("dataset_map_cache", &map_cache, py::arg("capacity") = py::none(), py::arg("threads") = py::none(),
          "libcam.dataset.map_cache (the docstring is there).");
}

}  // namespace libcam::python

#include "libcam/io/detail/json_format.hpp"

#include <nlohmann/json.hpp>

#include "libcam/convert/look_at_convert.hpp"
#include "libcam/error.hpp"
#include "libcam/io/detail/document.hpp"
#include "libcam/text/shown_value.hpp"

namespace libcam {

using ordered = nlohmann::ordered_json;  // output keeps the documented key order

namespace {

// Tolerance for derived keys that must agree with the primary ones (rvec with R, P with K[R|t]).
constexpr double kConsistencyTolerance = 1e-9;

// x + 0.0 turns -0 into +0, so files do not show "-0.0" for zero entries.
double tidy(double x) { return x + 0.0; }

template <class Matrix>
ordered matrix_json(const Matrix& m) {
    ordered rows = ordered::array();
    for (Eigen::Index r = 0; r < m.rows(); ++r) {
        ordered row = ordered::array();
        for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(tidy(m(r, c)));
        rows.push_back(row);
    }
    return rows;
}

template <class Vector>
ordered vector_json(const Vector& v) {
    ordered values = ordered::array();
    for (Eigen::Index i = 0; i < v.size(); ++i) values.push_back(tidy(v(i)));
    return values;
}

// Top-level keys one per line, matrices one row per line, everything else compact:
// readable, and still plain JSON.
std::string layout(const ordered& object) {
    std::string out = "{\n";
    std::size_t index = 0;
    for (const auto& [key, value] : object.items()) {
        out += "  " + ordered(key).dump() + ": ";
        const bool matrix = value.is_array() && !value.empty() && value.front().is_array();
        if (matrix) {
            out += "[\n";
            for (std::size_t r = 0; r < value.size(); ++r) {
                out += "    " + value[r].dump(-1, ' ', false) + (r + 1 < value.size() ? ",\n" : "\n");
            }
            out += "  ]";
        } else {
            out += value.dump();
        }
        out += ++index < object.size() ? ",\n" : "\n";
    }
    return out + "}\n";
}

// Reading: the file's keys through Field (document.hpp), whose errors name the file and
// the key, with the shapes this format uses: vectors, matrices, image sizes.
class Reader {
public:
    explicit Reader(const Field& top) : top_(top) {}

    // A key with a value (null counts as missing), or nothing.
    std::optional<Field> find(const char* key) const { return top_.find({key}); }
    bool has(const char* key) const { return find(key).has_value(); }
    Field field(const char* key) const { return top_.at({key}); }

    Eigen::VectorXd vector(const char* key, long expected = -1) const {
        const Field values = field(key);
        const long count = static_cast<long>(values.size());
        if (expected >= 0 && count != expected) {
            values.fail("expected " + std::to_string(expected) + " numbers, got " + std::to_string(count));
        }
        Eigen::VectorXd v(count);
        for (long i = 0; i < count; ++i) v(i) = values.item(static_cast<std::size_t>(i)).number();
        return v;
    }

    Eigen::MatrixXd matrix(const char* key, long rows, long cols) const {
        const Field value = field(key);
        const std::string shape = std::to_string(rows) + "x" + std::to_string(cols) + " nested arrays of numbers";
        if (value.node().kind != DocumentNode::Kind::Sequence || static_cast<long>(value.size()) != rows) {
            value.fail("expected " + shape + ", got " + value.shown());
        }
        Eigen::MatrixXd m(rows, cols);
        for (long r = 0; r < rows; ++r) {
            const Field row = value.item(static_cast<std::size_t>(r));
            if (row.node().kind != DocumentNode::Kind::Sequence || static_cast<long>(row.size()) != cols) {
                value.fail("expected " + shape + "; row " + std::to_string(r) + " is " + row.shown());
            }
            for (long c = 0; c < cols; ++c) m(r, c) = row.item(static_cast<std::size_t>(c)).number();
        }
        return m;
    }

    ImageSize image_size(const char* key) const {
        const Eigen::VectorXd v = vector(key, 2);
        for (int i = 0; i < 2; ++i) {
            if (v(i) != std::floor(v(i)) || v(i) < 1 || v(i) > static_cast<double>(kMaxImageSide)) {
                fail(key, "expected two integers in [1, " + std::to_string(kMaxImageSide) + "], got " + listed(v));
            }
        }
        return {static_cast<long>(v(0)), static_cast<long>(v(1))};
    }

    std::string string(const char* key) const { return field(key).text(); }

    // A key's error, whether or not the file has the key.
    [[noreturn]] void fail(const std::string& key, const std::string& what) const { top_.fail_at(key, what); }

    // Numbers as a message shows them: [0, 0, 640, 480].
    static std::string listed(const Eigen::VectorXd& v) {
        std::string out = "[";
        for (Eigen::Index i = 0; i < v.size(); ++i) out += (i == 0 ? "" : ", ") + format_number(v(i));
        return out + "]";
    }

private:
    Field top_;
};

// Runs a core validation and re-raises its message with the file name in front.
template <class F>
void validated(const std::string& source, F&& check) {
    try {
        check();
    } catch (const InvalidArgument& error) {
        throw FileError(source + ": " + error.what());
    }
}

Pose read_pose(const Reader& in, const std::string& source) {
    const Vec3 t = in.vector("t", 3);
    if (!in.has("R") && !in.has("rvec")) in.fail("R", "missing (give \"R\" or \"rvec\")");
    Pose pose;
    if (in.has("R")) {
        pose = Pose{in.matrix("R", 3, 3), t};
        validated(source, [&] { pose.validate("R"); });
        if (in.has("rvec")) {
            const Mat3 from_rvec = rotation_from_rvec(in.vector("rvec", 3));
            const double difference = (from_rvec - pose.R).cwiseAbs().maxCoeff();
            if (difference > kConsistencyTolerance) {
                in.fail("rvec", "disagrees with \"R\" (max difference " + format_number(difference) + ")");
            }
        }
    } else {
        pose = Pose::from_rvec(in.vector("rvec", 3), t);
    }
    return pose;
}

Camera read_calibrated(const Reader& in, const std::string& source) {
    Camera camera;
    const std::string model = in.string("model");
    const std::optional<LensType> type = lens_type_from_name(model);
    if (!type) in.fail("model", "unknown lens model " + shown_value(model));
    camera.lens.type = *type;
    camera.size = in.image_size("image_size");
    const Mat3 K = in.matrix("K", 3, 3);
    validated(source, [&] { camera.intrinsics = Intrinsics::from_K(K, "K"); });
    if (in.has("dist")) {
        const Eigen::VectorXd dist = in.vector("dist");
        camera.lens.coefficients.assign(dist.data(), dist.data() + dist.size());
    }
    validated(source, [&] { camera.lens.validate("dist"); });
    camera.pose = read_pose(in, source);
    if (in.has("P")) {
        const Mat34 P = in.matrix("P", 3, 4);
        const Mat34 expected = camera.P();
        const double difference = (P - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
        if (difference > kConsistencyTolerance) {
            in.fail("P", "disagrees with K [R | t] (max relative difference " + format_number(difference) + ")");
        }
    }
    validated(source, [&] { camera.validate(); });
    return camera;
}

CameraFile read_gl(const Reader& in, const std::string& source) {
    const Eigen::VectorXd viewport = in.vector("viewport", 4);
    if (viewport(0) != 0.0 || viewport(1) != 0.0) {
        in.fail("viewport", "must start at (0, 0) to describe a whole image, got " + Reader::listed(viewport));
    }
    DepthRange depth_range = DepthRange::MinusOneToOne;
    if (in.has("depth_range")) {
        const std::string name = in.string("depth_range");
        if (name == "zero-to-one") depth_range = DepthRange::ZeroToOne;
        else if (name != "minus-one-to-one") {
            in.fail("depth_range", "must be minus-one-to-one or zero-to-one, got " + shown_value(name));
        }
    }
    Camera camera;
    for (int i = 2; i < 4; ++i) {
        if (viewport(i) != std::floor(viewport(i)) || viewport(i) < 1 || viewport(i) > static_cast<double>(kMaxImageSide)) {
            in.fail("viewport", "width and height must be integers in [1, " + std::to_string(kMaxImageSide) + "]");
        }
    }
    camera.size = {static_cast<long>(viewport(2)), static_cast<long>(viewport(3))};
    const Mat4 projection = in.matrix("projection", 4, 4);
    const Mat4 view = in.matrix("view", 4, 4);
    validated(source, [&] { camera.intrinsics = intrinsics_from_opengl(projection, camera.size, depth_range).intrinsics; });
    if (view.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) in.fail("view", "last row must be 0 0 0 1");
    // view = diag(1, -1, -1) [R | t]
    const Eigen::Vector3d flip(1.0, -1.0, -1.0);
    camera.pose = Pose{flip.asDiagonal() * view.topLeftCorner<3, 3>(), flip.asDiagonal() * view.topRightCorner<3, 1>()};
    validated(source, [&] { camera.validate(); });
    return {camera, std::nullopt};
}

// The look-at camera a file records with "fov_axis". Its eye, gaze, up and fov are taken
// from the file when they agree with K, R, t (so JSON -> JSON is exact), refused when
// they do not.
LookAtCamera read_look_at_camera(const Reader& in, const Camera& camera, const std::string& source) {
    FovAxis axis{};
    validated(source, [&] { axis = fov_axis_from_string(in.string("fov_axis")); });
    LookAtCamera fov;
    try {
        fov = to_look_at_camera(camera, axis);
    } catch (const NotRepresentable& error) {
        in.fail("fov_axis", error.what());
    }
    const Basis basis = fov.basis();
    if (in.has("eye")) {
        const Vec3 eye = in.vector("eye", 3);
        if ((eye - fov.eye).norm() > kConsistencyTolerance * std::max(1.0, eye.norm())) {
            in.fail("eye", "disagrees with the camera centre -R^T t");
        }
        fov.eye = eye;
    }
    for (const char* key : {"gaze", "up"}) {
        if (!in.has(key)) continue;
        LookAtCamera candidate = fov;
        (key == std::string("gaze") ? candidate.gaze : candidate.up) = in.vector(key, 3);
        validated(source, [&] { candidate.validate(); });
        const Basis b = candidate.basis();
        if ((b.u - basis.u).norm() > kConsistencyTolerance || (b.v - basis.v).norm() > kConsistencyTolerance) {
            in.fail(key, "disagrees with R");
        }
        fov = candidate;
    }
    const std::optional<Field> angles = in.find("fov_deg");
    if (angles && angles->node().kind == DocumentNode::Kind::Map) {
        const char* name = axis == FovAxis::Both ? "horizontal" : to_string(axis).data();
        if (const std::optional<Field> angle = angles->find({name})) {
            const double stored = angle->number();
            if (std::abs(stored - fov.fov_deg) > kConsistencyTolerance * fov.fov_deg) {
                in.fail("fov_deg", std::string(name) + " " + format_number(stored) + " disagrees with K (" +
                                       format_number(fov.fov_deg) + ")");
            }
            fov.fov_deg = stored;
        }
    }
    return fov;
}

// The keys every libcam JSON camera has, and all the reader needs: model, image_size, K,
// dist, R, t.
ordered camera_keys(const Camera& camera) {
    ordered out;
    out["model"] = lens_info(camera.lens.type).name;
    out["image_size"] = {camera.size.width, camera.size.height};
    out["K"] = matrix_json(camera.intrinsics.K());
    out["dist"] = camera.lens.coefficients;
    out["R"] = matrix_json(camera.pose.R);
    out["t"] = vector_json(camera.pose.t);
    return out;
}

}  // namespace

std::string format_json(const Camera& camera, const std::optional<LookAtCamera>& look_at_camera) {
    const FovDescription fov = describe_fov(camera);
    ordered out = camera_keys(camera);
    out["rvec"] = vector_json(camera.pose.rvec());
    out["P"] = matrix_json(camera.P());
    out["camera_center"] = vector_json(fov.eye);
    out["fov_deg"] = ordered{{"horizontal", fov.fov_deg.horizontal},
                             {"vertical", fov.fov_deg.vertical},
                             {"diagonal", fov.fov_deg.diagonal}};
    out["frustum"] = ordered{{"left", tidy(fov.frustum.left)},
                             {"right", tidy(fov.frustum.right)},
                             {"bottom", tidy(fov.frustum.bottom)},
                             {"top", tidy(fov.frustum.top)}};
    // A look-at camera's own eye and up as the user gave them (the centre -R^T t carries
    // the rounding of R and t); otherwise the camera's centre and its own up.
    out["eye"] = vector_json(look_at_camera ? look_at_camera->eye : fov.eye);
    out["gaze"] = vector_json(look_at_camera ? Vec3(look_at_camera->gaze.normalized()) : fov.gaze);
    out["up"] = vector_json(look_at_camera ? look_at_camera->up : fov.up);
    if (look_at_camera) out["fov_axis"] = to_string(look_at_camera->fov_axis);
    ordered axes = ordered::array();
    for (FovAxis axis : fov.fov_axes) axes.push_back(to_string(axis));
    out["fov_axes"] = axes;
    out["not_fov_because"] = fov.deviations;
    return layout(out);
}

std::string format_gl_json(const GlCamera& gl, const ImageSize& size) {
    ordered out;
    out["format"] = "opengl";
    out["image_size"] = {size.width, size.height};
    out["projection"] = matrix_json(gl.projection);
    out["view"] = matrix_json(gl.view);
    out["viewport"] = gl.viewport;
    out["near"] = gl.near;
    out["far"] = gl.far;
    out["depth_range"] = gl.depth_range == DepthRange::ZeroToOne ? "zero-to-one" : "minus-one-to-one";
    out["layout"] = "row-major: upload with transpose = GL_TRUE; window origin bottom-left, pixel centres at +0.5";
    return layout(out);
}

std::string format_json_camera_object(const Camera& camera) { return camera_keys(camera).dump(); }

Camera read_json_camera_object(const Field& object) {
    if (object.node().kind != DocumentNode::Kind::Map) {
        object.fail("expected a camera (\"model\", \"image_size\", \"K\", ...), got " + object.shown());
    }
    return read_calibrated(Reader(object), object.source());
}

CameraFile parse_json_camera(std::string_view text, const std::string& source) {
    const DocumentNode root = parse_json_tree(text, source);
    if (root.kind != DocumentNode::Kind::Map) throw FileError(source + ": expected a JSON object at the top level");
    const Reader in(Field(root, "", source));
    if (in.has("projection")) return read_gl(in, source);

    CameraFile file{read_calibrated(in, source), std::nullopt};
    if (in.has("fov_axis")) file.look_at_camera = read_look_at_camera(in, file.camera, source);
    return file;
}

}  // namespace libcam

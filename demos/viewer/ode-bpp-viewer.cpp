// ode-bpp-viewer: any registered scene, drawn with ODE's drawstuff.
//
//   ode-bpp-viewer [SCENE] [--solver NAME] [--frames N] [--screenshot FILE.ppm|FILE.png] [--list]
//
// Geoms are drawn generically by class from the scene's space, so a scene needs no drawing code.
// Keys: n / p next / previous scene, s next solver (rebuilds), r restart, space pause,
// c camera follows the bodies (on) or stays where the mouse puts it (off).
// The window shows the scene, the solver, the simulated time and the solve time per step in its
// top left corner (so screenshots describe themselves) and in its title.
#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <drawstuff/drawstuff.h>
#include <ode/mlcp.h>
#include <ode/ode.h>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "overlay.h"
#include "scenes/scene.h"

namespace {

using namespace ode_bpp::scenes;

constexpr int kWindowWidth = 800, kWindowHeight = 600;
// Looking from the +x, -y side: drawstuff's light comes from +x, so the faces in view are lit.
constexpr double kCameraHeading = 125.0;     // degrees, 0 looks along +x
constexpr double kCameraPitch = 20.0;        // degrees below the horizontal
constexpr double kCameraMinDistance = 3.0;   // [m]
constexpr double kCameraFraming = 1.1;       // distance per metre of the bodies' extent
constexpr double kCameraSmoothing = 0.1;     // share of the way to the new target per frame
constexpr float kGeomlessBodyMarker = 0.05f; // radius of the sphere drawn for a body without geoms [m]

constexpr int kExitFailure = 1;  ///< the window or the screenshot failed
constexpr int kExitUsage = 2;    ///< bad arguments, unknown scene or solver

const char* const kUsage =
    "usage: ode-bpp-viewer [SCENE] [--solver NAME] [--frames N] [--screenshot FILE.ppm|FILE.png]\n"
    "       ode-bpp-viewer --list | --help\n"
    "Draws SCENE (default: the first) stepped with an MLCP solver inside dWorldStep (default bpp).\n"
    "  --frames N      quit after N frames (0: run until the window is closed)\n"
    "  --screenshot F  write the last frame to F (.ppm or .png); needs --frames\n"
    "  --list          the scenes and solvers\n"
    "       drawstuff's own flags -notex, -noshadow and -pause are passed on.\n"
    "keys:  n/p next/previous scene, s next solver, r restart, space pause, c camera follow on/off\n"
    "exit status: 0 done, 1 the screenshot could not be written, 2 bad arguments\n";

struct Options {
    std::string scene;                       ///< empty: the first registered scene
    std::string solver;                      ///< empty: "bpp" if registered, else "dantzig"
    long frames = 0;                         ///< quit after this many frames; 0: run until closed
    std::string screenshot;                  ///< written after the last frame; empty: none
    bool list = false;
    bool help = false;
    std::vector<std::string> drawstuff_flags;
};

long frame_count(const std::string& text) {
    char* end = nullptr;
    const long n = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || n < 0) throw std::invalid_argument("--frames needs a count >= 0, got '" + text + "'");
    return n;
}

/// Parses the command line; throws std::invalid_argument on a bad one.
Options parse_options(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
            return argv[++i];
        };
        if (arg == "--help" || arg == "-h") options.help = true;
        else if (arg == "--solver") options.solver = value();
        else if (arg == "--frames") options.frames = frame_count(value());
        else if (arg == "--screenshot") options.screenshot = value();
        else if (arg == "--list") options.list = true;
        else if (arg == "-notex" || arg == "-noshadow" || arg == "-noshadows" || arg == "-pause")
            options.drawstuff_flags.push_back(arg);
        else if (!arg.empty() && arg[0] != '-' && options.scene.empty()) options.scene = arg;
        else throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
    if (!options.screenshot.empty() && options.frames == 0)
        throw std::invalid_argument("--screenshot needs --frames N (the shot is taken after the last frame)");
    return options;
}

size_t index_of(const std::vector<std::string>& names, const std::string& name, const char* what) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return size_t(it - names.begin());
    std::string known;
    for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument(std::string("unknown ") + what + " '" + name + "'; valid: " + known);
}

// ---------------------------------------------------------------------------------------------
// Screenshots

/// An RGB image, 8 bits per channel, top row first.
struct Image {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
};

/// The current viewport of the back buffer, as drawn so far in this frame.
Image read_frame_buffer() {
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    Image image{viewport[2], viewport[3], {}};
    const size_t row = size_t(image.width) * 3;
    std::vector<unsigned char> bottom_up(row * size_t(image.height));
    glFinish();
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(viewport[0], viewport[1], image.width, image.height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
    image.rgb.resize(bottom_up.size());
    for (int y = 0; y < image.height; ++y)  // OpenGL's rows run bottom-up
        std::memcpy(&image.rgb[size_t(y) * row], &bottom_up[size_t(image.height - 1 - y) * row], row);
    return image;
}

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// Writes binary PPM (P6); throws std::runtime_error if the file cannot be written.
void write_ppm(const Image& image, const std::string& path) {
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!file) throw std::runtime_error("cannot open " + path);
    std::fprintf(file.get(), "P6\n%d %d\n255\n", image.width, image.height);
    if (std::fwrite(image.rgb.data(), 1, image.rgb.size(), file.get()) != image.rgb.size())
        throw std::runtime_error("cannot write " + path);
}

/// Writes PNG through libpng's simplified API; throws std::runtime_error on failure.
void write_png(const Image& image, const std::string& path) {
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    png.width = png_uint_32(image.width);
    png.height = png_uint_32(image.height);
    png.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&png, path.c_str(), 0, image.rgb.data(), 0, nullptr))
        throw std::runtime_error("cannot write " + path + ": " + png.message);
}

void write_image(const Image& image, const std::string& path) {
    if (ends_with(path, ".png")) write_png(image, path);
    else if (ends_with(path, ".ppm")) write_ppm(image, path);
    else throw std::runtime_error("screenshot " + path + ": name it .ppm or .png");
}

// ---------------------------------------------------------------------------------------------
// Drawing geoms by class

/// A distinct colour per body index (golden-ratio hue steps), so neighbours differ.
void set_body_colour(size_t index, bool enabled) {
    const double hue = std::fmod(0.61803398875 * double(index), 1.0) * 6.0;
    const double f = hue - std::floor(hue);
    const float shade = enabled ? 1.0f : 0.5f;  // bodies put to sleep by ODE are drawn darker
    float r = 0, g = 0, b = 0;
    switch (int(hue)) {
    case 0: r = 1, g = float(f); break;
    case 1: r = float(1 - f), g = 1; break;
    case 2: g = 1, b = float(f); break;
    case 3: g = float(1 - f), b = 1; break;
    case 4: r = float(f), b = 1; break;
    default: r = 1, b = float(1 - f); break;
    }
    const auto soften = [shade](float c) { return shade * (0.35f + 0.65f * c); };
    dsSetColor(soften(r), soften(g), soften(b));
}

void draw_trimesh(dGeomID g) {
    static const double origin[3] = {0, 0, 0};
    static const double identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    const int count = dGeomTriMeshGetTriangleCount(g);
    for (int i = 0; i < count; ++i) {
        dVector3 v0, v1, v2;
        dGeomTriMeshGetTriangle(g, i, &v0, &v1, &v2);  // world frame
        dsDrawTriangleD(origin, identity, v0, v1, v2, 1);
    }
}

/// Draws one primitive geom; planes, rays and classes drawstuff has no shape for are skipped.
void draw_primitive(dGeomID g) {
    const int cls = dGeomGetClass(g);
    if (cls == dTriMeshClass) {
        draw_trimesh(g);
        return;
    }
    if (cls != dBoxClass && cls != dSphereClass && cls != dCapsuleClass && cls != dCylinderClass) return;
    const dReal* pos = dGeomGetPosition(g);  // only placeable geoms get this far
    const dReal* R = dGeomGetRotation(g);
    dReal radius = 0, length = 0;
    switch (cls) {
    case dBoxClass: {
        dVector3 sides;
        dGeomBoxGetLengths(g, sides);
        dsDrawBoxD(pos, R, sides);
        break;
    }
    case dSphereClass: dsDrawSphereD(pos, R, float(dGeomSphereGetRadius(g))); break;
    case dCapsuleClass:
        dGeomCapsuleGetParams(g, &radius, &length);
        dsDrawCapsuleD(pos, R, float(length), float(radius));
        break;
    case dCylinderClass:
        dGeomCylinderGetParams(g, &radius, &length);
        dsDrawCylinderD(pos, R, float(length), float(radius));
        break;
    default: break;
    }
}

/// Geoms of a space and its sub-spaces, depth first.
void collect_geoms(dSpaceID space, std::vector<dGeomID>& out) {
    const int n = dSpaceGetNumGeoms(space);
    for (int i = 0; i < n; ++i) {
        dGeomID g = dSpaceGetGeom(space, i);
        if (dGeomIsSpace(g)) collect_geoms(reinterpret_cast<dSpaceID>(g), out);
        else out.push_back(g);
    }
}

// ---------------------------------------------------------------------------------------------
// The viewer

class Viewer {
public:
    explicit Viewer(const Options& options) : options_(options), scenes_(scene_names()), solvers_(registered_solvers()) {
        if (scenes_.empty()) throw std::runtime_error("no scenes are registered");
        scene_index_ = options.scene.empty() ? 0 : index_of(scenes_, options.scene, "scene");
        const std::string solver = !options.solver.empty() ? options.solver
                                   : is_solver_registered("bpp") ? "bpp" : "dantzig";
        solver_index_ = index_of(solvers_, solver, "solver");
    }

    void start() {
        std::printf("%s", kUsage);
        if (!overlay_.load()) std::printf("no X font for the text in the window; the title still says it all\n");
        rebuild();
    }

    /// drawstuff's per-frame callback: advance one step unless paused, draw, handle --frames.
    void frame(bool drawstuff_paused) {
        if (!paused_ && !drawstuff_paused) advance();
        if (follow_) follow_camera(false);
        draw();
        overlay_.draw(overlay_lines());
        ++frames_;
        update_title();
        if (options_.frames > 0 && frames_ >= options_.frames) finish_run();
    }

    void key(int cmd) {
        switch (cmd) {
        case 'n': scene_index_ = (scene_index_ + 1) % scenes_.size(); rebuild(); break;
        case 'p': scene_index_ = (scene_index_ + scenes_.size() - 1) % scenes_.size(); rebuild(); break;
        case 's': solver_index_ = (solver_index_ + 1) % solvers_.size(); rebuild(); break;
        case 'r': rebuild(); break;
        case ' ': paused_ = !paused_; break;
        case 'c': follow_ = !follow_; break;
        default: break;
        }
    }

    /// drawstuff's stop callback: one summary line.
    void stop() const { std::printf("%s\n", status_line().c_str()); }

    bool screenshot_failed() const { return screenshot_failed_; }

private:
    /// A fresh world and scene for the current scene and solver (new world first: ODE stays
    /// initialised while the old one is destroyed).
    void rebuild() {
        SceneParams params;
        params.solver = solvers_[solver_index_];
        std::unique_ptr<Scene> scene = make_scene(scenes_[scene_index_]);
        if (!scene) throw std::runtime_error("the registry cannot make scene " + scenes_[scene_index_]);
        params.seconds = scene->default_seconds();
        auto world = std::make_unique<SceneWorld>(params);
        scene->build(*world);
        world_ = std::move(world);
        scene_ = std::move(scene);
        judged_ = false;
        step_failed_ = false;
        std::printf("scene %s (%s), solver %s\n", scene_->name().c_str(), scene_->description().c_str(),
                    params.solver.c_str());
        follow_camera(true);
    }

    void advance() {
        if (step_failed_) return;
        scene_->control(*world_, world_->time());
        if (!world_->step()) {
            step_failed_ = true;
            std::printf("%s: world step failed at t = %.3f s (paused; r restarts)\n", scene_->name().c_str(),
                        world_->time());
        }
        if (!judged_ && world_->time() >= world_->params().seconds - 0.5 * world_->params().step) {
            judged_ = true;
            const SuccessReport report = scene_->success(*world_);
            std::printf("%s after %.2f s with %s: %s - %s\n", scene_->name().c_str(), world_->time(),
                        world_->params().solver.c_str(), report.ok ? "success" : "FAILED", report.detail.c_str());
        }
    }

    void draw() const {
        std::vector<dGeomID> geoms;
        collect_geoms(world_->space(), geoms);
        const std::vector<dBodyID>& bodies = world_->bodies();
        for (dGeomID g : geoms) {
            dBodyID body = dGeomGetBody(g);
            if (body) {
                const size_t index = size_t(std::find(bodies.begin(), bodies.end(), body) - bodies.begin());
                set_body_colour(index, dBodyIsEnabled(body) != 0);
                dsSetTexture(DS_WOOD);
            } else {
                dsSetColor(0.6f, 0.6f, 0.62f);
                dsSetTexture(DS_NONE);
            }
            draw_primitive(g);
        }
        // Bodies without geoms (e.g. cable links that never collide) still show where they are.
        for (size_t i = 0; i < bodies.size(); ++i) {
            if (dBodyGetFirstGeom(bodies[i])) continue;
            set_body_colour(i, dBodyIsEnabled(bodies[i]) != 0);
            dsSetTexture(DS_NONE);
            dsDrawSphereD(dBodyGetPosition(bodies[i]), dBodyGetRotation(bodies[i]), kGeomlessBodyMarker);
        }
    }

    /// Looks at the centre of the bodies' bounding box from a distance that frames it.
    void follow_camera(bool snap) {
        std::vector<dGeomID> geoms;
        collect_geoms(world_->space(), geoms);
        double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        for (dGeomID g : geoms) {
            if (!dGeomGetBody(g) || dGeomGetClass(g) == dPlaneClass) continue;
            dReal box[6];
            dGeomGetAABB(g, box);
            for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(box[2 * k])), hi[k] = std::max(hi[k], double(box[2 * k + 1]));
        }
        if (!(lo[0] <= hi[0]) || !std::isfinite(hi[0] - lo[0])) return;  // no finite bodies to look at
        double extent = 0;
        for (int k = 0; k < 3; ++k) extent = std::max(extent, hi[k] - lo[k]);
        const double alpha = snap ? 1.0 : kCameraSmoothing;
        for (int k = 0; k < 3; ++k) camera_target_[k] += alpha * (0.5 * (lo[k] + hi[k]) - camera_target_[k]);
        camera_distance_ += alpha * (std::max(kCameraMinDistance, kCameraFraming * extent) - camera_distance_);
        const double pitch = kCameraPitch * M_PI / 180.0, heading = kCameraHeading * M_PI / 180.0;
        const double horizontal = camera_distance_ * std::cos(pitch);
        float xyz[3] = {float(camera_target_[0] - horizontal * std::cos(heading)),
                        float(camera_target_[1] - horizontal * std::sin(heading)),
                        float(camera_target_[2] + camera_distance_ * std::sin(pitch))};
        float hpr[3] = {float(kCameraHeading), float(-kCameraPitch), 0.0f};
        dsSetViewpoint(xyz, hpr);
    }

    std::string status_line() const {
        char line[256];
        dMLCPStepStats last{}, total{};
        const bool solved = dWorldGetMLCPStats(world_->world(), &last, &total) != 0;
        const double mean_ms = solved && total.steps > 0 ? 1e3 * total.seconds / double(total.steps) : 0.0;
        std::snprintf(line, sizeof line, "%s | solver %s | t = %.2f s | solve %.3f ms (mean %.3f ms, %d rows)%s%s",
                      scene_->name().c_str(), world_->params().solver.c_str(), world_->time(),
                      solved ? 1e3 * last.seconds : 0.0, mean_ms, solved ? static_cast<int>(last.rows) : 0,
                      paused_ ? " | paused" : "", step_failed_ ? " | STEP FAILED" : "");
        return line;
    }

    /// What the window shows in its corner: scene, solver, simulated time, solve time per step.
    std::vector<std::string> overlay_lines() const {
        constexpr size_t kMaxDescription = 60;
        dMLCPStepStats last{}, total{};
        const bool solved = dWorldGetMLCPStats(world_->world(), &last, &total) != 0;
        std::string description = scene_->description();
        if (description.size() > kMaxDescription) description = description.substr(0, kMaxDescription - 3) + "...";
        char solver[128], time[64], solve[128];
        std::snprintf(solver, sizeof solver, "solver %s%s%s", world_->params().solver.c_str(),
                      paused_ ? "   (paused)" : "", step_failed_ ? "   STEP FAILED" : "");
        std::snprintf(time, sizeof time, "t = %.2f s simulated", world_->time());
        if (solved)
            std::snprintf(solve, sizeof solve, "solve %.3f ms this step, %.3f ms mean per step, %d rows",
                          1e3 * last.seconds, total.steps > 0 ? 1e3 * total.seconds / double(total.steps) : 0.0,
                          static_cast<int>(last.rows));
        else
            std::snprintf(solve, sizeof solve, "solve: no constraints yet");
        return {scene_->name() + ": " + description, solver, time, solve};
    }

    /// The title goes straight to the X window drawstuff made current for its GL context.
    void update_title() {
        const std::string title = "ode-bpp-viewer: " + status_line();
        if (title == title_) return;
        title_ = title;
        Display* display = glXGetCurrentDisplay();
        const GLXDrawable window = glXGetCurrentDrawable();
        if (!display || !window) return;
        XStoreName(display, Window(window), title_.c_str());
    }

    void finish_run() {
        if (!options_.screenshot.empty()) {
            try {
                write_image(read_frame_buffer(), options_.screenshot);
                std::printf("screenshot %s after %ld frames\n", options_.screenshot.c_str(), frames_);
            } catch (const std::exception& e) {
                std::fprintf(stderr, "ode-bpp-viewer: %s\n", e.what());
                screenshot_failed_ = true;
            }
        }
        dsStop();
    }

    Options options_;
    std::vector<std::string> scenes_, solvers_;
    size_t scene_index_ = 0, solver_index_ = 0;
    std::unique_ptr<SceneWorld> world_;
    std::unique_ptr<Scene> scene_;
    bool paused_ = false, follow_ = true, judged_ = false, step_failed_ = false, screenshot_failed_ = false;
    long frames_ = 0;
    double camera_target_[3] = {0, 0, 0};
    double camera_distance_ = kCameraMinDistance;
    std::string title_;
    ode_bpp::viewer::TextOverlay overlay_;
};

// drawstuff takes plain function pointers; they reach the one viewer through this pointer.
Viewer* g_viewer = nullptr;

void on_start() { g_viewer->start(); }
void on_step(int pause) { g_viewer->frame(pause != 0); }
void on_command(int cmd) { g_viewer->key(cmd); }
void on_stop() { g_viewer->stop(); }

void print_list() {
    std::printf("scenes:");
    for (const std::string& name : scene_names()) std::printf(" %s", name.c_str());
    std::printf("\nsolvers: %s\n", dListMLCPSolvers());
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options options = parse_options(argc, argv);
        if (options.help) {
            std::printf("%s", kUsage);
            return EXIT_SUCCESS;
        }
        if (options.list) {
            print_list();
            return EXIT_SUCCESS;
        }
        Viewer viewer(options);
        g_viewer = &viewer;
        dsFunctions fn{};
        fn.version = DS_VERSION;
        fn.start = &on_start;
        fn.step = &on_step;
        fn.command = &on_command;
        fn.stop = &on_stop;
        fn.path_to_textures = ODE_BPP_DRAWSTUFF_TEXTURES;
        std::vector<char*> ds_argv = {argv[0]};
        std::vector<std::string> flags = options.drawstuff_flags;
        for (std::string& flag : flags) ds_argv.push_back(flag.data());
        dsSimulationLoop(int(ds_argv.size()), ds_argv.data(), kWindowWidth, kWindowHeight, &fn);
        g_viewer = nullptr;
        return viewer.screenshot_failed() ? kExitFailure : EXIT_SUCCESS;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "ode-bpp-viewer: %s (ode-bpp-viewer --help for the usage)\n", e.what());
        return kExitUsage;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ode-bpp-viewer: %s\n", e.what());
        return kExitFailure;
    }
}

// meshwave view-rd STREAM.mwv: the bytes a client needs before what it
// shows is within N pixels of the complete mesh, along camera paths, in
// the screen-space-error view order (a view request with screen_error N:
// what `meshwave fetch --view ... --screen-error N` and the viewer
// receive, each camera continuing from what the ones before brought) and
// in the uniform rd order (the shortest prefix that serves every camera
// of the path). Units are judged by the stream's measured errors
// (meshwave/screen_errors.h), as the server judges them; `--bound` judges
// them by the quantisers' bound instead.
//
// The error a camera shows: over the finest vertices inside its frustum,
// the largest distance along the complete mesh's vertex normal between
// the decoded vertex and the complete one (to first order the distance to
// the complete surface: a slide along the surface draws the same image),
// in pixels at the vertex's depth. Occlusion is ignored: hidden vertices
// count too, so the figure is a bound on what is drawn.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "complete_stream.h"
#include "meshwave/progression.h"
#include "meshwave/region.h"
#include "meshwave/screen_errors.h"

namespace meshwave::cli {
namespace {

// Area-weighted unit normals of the complete mesh. Computed here, not
// with the codec's own (which measures the errors this command judges):
// the instrument stays apart from what it measures.
std::vector<Vec3> VertexNormals(const std::vector<Vec3>& positions,
                                const std::vector<Face>& faces) {
  std::vector<Vec3> normals(positions.size(), Vec3::Zero());
  for (const Face& f : faces) {
    const Vec3 n = (positions[f[1]] - positions[f[0]])
                       .cross(positions[f[2]] - positions[f[0]]);
    for (uint32_t v : f) normals[v] += n;
  }
  for (Vec3& n : normals) {
    const double length = n.norm();
    n = length > 0 ? Vec3(n / length) : Vec3::Zero();
  }
  return normals;
}

struct ViewArgs {
  std::string file;
  std::string tolerances = "1,4";
  uint32_t width = 1280, height = 720;
  double fov = 45;
  int orbit_cameras = 8;
  bool bound = false;
};

struct CameraPath {
  std::string name;
  std::vector<ViewRegion> cameras;
};

// The largest projected normal deviation (pixels) of `got` from the
// complete mesh over the vertices `camera` sees.
double ViewError(const ViewRegion& camera, const CompleteStream& s,
                 const std::vector<Vec3>& normals,
                 const std::vector<Vec3>& got) {
  const Vec3 forward = camera.direction.normalized();
  Vec3 right = forward.cross(Vec3::UnitY());
  if (right.norm() < 1e-9) right = forward.cross(Vec3::UnitZ());
  right.normalize();
  const Vec3 up = right.cross(forward);
  const double tan_half = std::tan(camera.fov_degrees * std::numbers::pi / 360);
  const double half_h = 0.5 * camera.height, half_w = 0.5 * camera.width;
  double worst = 0;
  for (size_t v = 0; v < s.full.size(); ++v) {
    const Vec3 d = s.full[v] - camera.eye;
    const double z = d.dot(forward);
    if (!(z > 0)) continue;
    const double px_per_unit = half_h / (z * tan_half);
    const double x = d.dot(right) * px_per_unit, y = d.dot(up) * px_per_unit;
    if (std::abs(x) > half_w || std::abs(y) > half_h) continue;
    worst = std::max(
        worst, std::abs((got[v] - s.full[v]).dot(normals[v])) * px_per_unit);
  }
  return worst;
}

ViewRegion Camera(const ViewArgs& args, const Vec3& eye, const Vec3& target) {
  ViewRegion c;
  c.eye = eye;
  c.direction = target - eye;
  c.fov_degrees = args.fov;
  c.width = args.width;
  c.height = args.height;
  return c;
}

// An orbit around the bounding sphere, 20 degrees above its equator, at
// the distance that fits the sphere to the screen's height; and a zoom
// along the normal onto the vertex farthest along a fixed direction, from
// twice the sphere's radius to an eighth of it.
std::vector<CameraPath> Paths(const ViewArgs& args, const CompleteStream& s,
                              const std::vector<Vec3>& normals) {
  Vec3 lo = s.full[0], hi = s.full[0];
  for (const Vec3& p : s.full) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * (hi - lo).norm();
  const double distance = radius / std::sin(args.fov * std::numbers::pi / 360);
  CameraPath orbit{"orbit", {}};
  const double elevation = 20 * std::numbers::pi / 180;
  for (int k = 0; k < args.orbit_cameras; ++k) {
    const double azimuth = 2 * std::numbers::pi * k / args.orbit_cameras;
    const Vec3 at(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                  std::cos(elevation) * std::cos(azimuth));
    orbit.cameras.push_back(Camera(args, centre + distance * at, centre));
  }
  const Vec3 direction = Vec3(0.31, 0.85, 0.42).normalized();
  size_t target = 0;
  for (size_t v = 0; v < s.full.size(); ++v) {
    if (s.full[v].dot(direction) > s.full[target].dot(direction)) target = v;
  }
  const Vec3 along = normals[target].norm() > 0 ? normals[target] : direction;
  CameraPath zoom{"zoom", {}};
  for (double f : {2.0, 1.0, 0.5, 0.25, 0.125}) {
    zoom.cameras.push_back(
        Camera(args, s.full[target] + f * radius * along, s.full[target]));
  }
  return {orbit, zoom};
}

Result<std::vector<double>> ParseTolerances(const std::string& text) {
  std::vector<double> out;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    double px = 0;
    try {
      px = std::stod(item);
    } catch (...) {
      return InvalidArgument("--tolerances: \"" + item + "\" is not a number");
    }
    if (!(px > 0 && px <= 1000))
      return InvalidArgument("--tolerances: each in (0, 1000] pixels");
    out.push_back(px);
  }
  if (out.empty()) return InvalidArgument("--tolerances: none given");
  return out;
}

// The view order along `path` at `tolerance`: bytes sent, and the largest
// error any camera showed after its request.
struct ViewResult {
  uint64_t bytes = 0;
  double worst_px = 0;
};
Result<ViewResult> ViewOrderAlong(const CompleteStream& s,
                                  const std::vector<Vec3>& normals,
                                  const CameraPath& path, double tolerance,
                                  const StreamScreenErrors* measured) {
  MW_ASSIGN_OR_RETURN(auto d, ProgressiveDecoder::Create(s.header()));
  ViewResult out;
  for (const ViewRegion& camera : path.cameras) {
    const Region region{camera, tolerance};
    for (const StreamUnit& u :
         RegionOrder(s.header(), *s.precincts, s.part_lengths, region,
                     d->held(), -1, measured)) {
      MW_RETURN_IF_ERROR(s.Send(*d, u));
      out.bytes += s.UnitBytes(u);
    }
    out.worst_px =
        std::max(out.worst_px, ViewError(camera, s, normals, d->Positions()));
  }
  return out;
}

// The uniform rd order: per camera, the payload bytes of the shortest
// prefix after which it shows at most each tolerance.
Result<std::vector<std::vector<uint64_t>>> RdBytes(
    const CompleteStream& s, const std::vector<Vec3>& normals,
    const std::vector<ViewRegion>& cameras,
    const std::vector<double>& tolerances) {
  MW_ASSIGN_OR_RETURN(auto d, ProgressiveDecoder::Create(s.header()));
  constexpr uint64_t kUnset = ~uint64_t{0};
  std::vector<std::vector<uint64_t>> out(
      cameras.size(), std::vector<uint64_t>(tolerances.size(), kUnset));
  uint64_t bytes = 0;
  const std::vector<uint32_t> order = PacketOrder(s.header(), Progression::kRd);
  for (size_t k = 0; k <= order.size(); ++k) {
    if (k > 0) {
      MW_RETURN_IF_ERROR(d->AddPacket(order[k - 1], s.payload[order[k - 1]]));
      bytes += s.payload[order[k - 1]].size();
    }
    bool all = true;
    const std::vector<Vec3> got = d->Positions();
    for (size_t c = 0; c < cameras.size(); ++c) {
      const double px = ViewError(cameras[c], s, normals, got);
      for (size_t t = 0; t < tolerances.size(); ++t) {
        if (out[c][t] == kUnset && px <= tolerances[t]) out[c][t] = bytes;
        all = all && out[c][t] != kUnset;
      }
    }
    if (all) break;
  }
  return out;
}

Status Run(const ViewArgs& args) {
  MW_ASSIGN_OR_RETURN(std::unique_ptr<CompleteStream> loaded,
                      LoadCompleteStream(args.file, "view-rd"));
  const CompleteStream& s = *loaded;
  MW_ASSIGN_OR_RETURN(std::vector<double> tolerances,
                      ParseTolerances(args.tolerances));
  const std::vector<Vec3> normals = VertexNormals(s.full, s.faces);
  MW_ASSIGN_OR_RETURN(
      StreamScreenErrors measured,
      StreamScreenErrors::Measure(s.header(), s.payload, *s.precincts));
  uint64_t total = 0;
  for (std::string_view p : s.payload) total += p.size();
  std::printf(
      "%s: %zu finest vertices, %llu payload bytes; screen %ux%u, fov %g "
      "degrees\n",
      args.file.c_str(), s.full.size(), static_cast<unsigned long long>(total),
      args.width, args.height, args.fov);
  std::printf("%-6s %7s %9s %12s %10s %12s %9s\n", "path", "cameras",
              "tolerance", "view bytes", "worst px", "rd bytes", "view/rd");
  for (const CameraPath& path : Paths(args, s, normals)) {
    MW_ASSIGN_OR_RETURN(auto rd, RdBytes(s, normals, path.cameras, tolerances));
    for (size_t t = 0; t < tolerances.size(); ++t) {
      MW_ASSIGN_OR_RETURN(ViewResult view,
                          ViewOrderAlong(s, normals, path, tolerances[t],
                                         args.bound ? nullptr : &measured));
      uint64_t rd_bytes = 0;
      for (const auto& camera : rd) rd_bytes = std::max(rd_bytes, camera[t]);
      std::printf(
          "%-6s %7zu %7g px %12llu %10.2f %12llu %9.2f\n", path.name.c_str(),
          path.cameras.size(), tolerances[t],
          static_cast<unsigned long long>(view.bytes), view.worst_px,
          static_cast<unsigned long long>(rd_bytes),
          rd_bytes > 0
              ? static_cast<double>(view.bytes) / static_cast<double>(rd_bytes)
              : INFINITY);  // the header alone is within the tolerance
    }
  }
  return Status::Ok();
}

}  // namespace

void AddViewCommand(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand(
      "view-rd",
      "The bytes a client needs before every camera of a path (an orbit, a "
      "zoom onto a detail) "
      "shows the mesh within N pixels of the complete stream's, in the "
      "screen-space-error view "
      "order and in the uniform rd order, on a complete .mwv stream");
  cmd->add_option("stream", args->file,
                  "A complete .mwv stream (meshwave encode)")
      ->required();
  cmd->add_option("--tolerances", args->tolerances,
                  "Comma-separated screen-space errors in pixels")
      ->capture_default_str();
  cmd->add_option("--width", args->width, "Screen width in pixels")
      ->check(CLI::Range(1u, kMaxScreenPixels))
      ->capture_default_str();
  cmd->add_option("--height", args->height, "Screen height in pixels")
      ->check(CLI::Range(1u, kMaxScreenPixels))
      ->capture_default_str();
  cmd->add_option("--fov", args->fov, "Vertical field of view in degrees")
      ->check(CLI::Range(1.0, 179.0))
      ->capture_default_str();
  cmd->add_option("--orbit-cameras", args->orbit_cameras,
                  "Cameras on the orbit")
      ->check(CLI::Range(1, 360))
      ->capture_default_str();
  cmd->add_flag("--bound", args->bound,
                "Judge units by the quantiser's bound on what they hold, as a "
                "server without measured errors does, instead of by the "
                "stream's measured errors");
  cmd->callback([args, &exit_code] {
    if (Status s = Run(*args); !s.ok()) exit_code = Fail("view-rd", s);
  });
}

}  // namespace meshwave::cli

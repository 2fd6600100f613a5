// Z-buffer rasterizer of the scene's textured quads and furniture meshes
// (triangle_raster.h): for the quads a depth/id pass (with
// back-face culling and near-plane clipping) followed by one perspective-
// correct bilinear texture lookup per pixel into the session's prepared
// radiance textures. Mirror quads (Quad::mirror_reflectance > 0, window
// glass) get a second pass of the scene reflected in their plane, limited to
// their pixels and to what lies beyond them, blended in by Schlick's Fresnel
// term. Single-threaded and deterministic.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"
#include "slam/synthetic/light/lighting.h"
#include "slam/synthetic/scene/scene.h"

namespace duskmap {

struct RenderedView {
  cv::Mat radiance;       // CV_32FC3 linear BGR nits; 0 where nothing is seen
  cv::Mat depth_m;        // CV_32FC1 distance along the optical axis; 0 = nothing
  // CV_32SC1: the quad index, or quads.size() + the mesh index where a
  // furniture mesh is seen; -1 = nothing.
  cv::Mat surface_id;
  cv::Mat cos_incidence;  // CV_32FC1 cosine between viewing ray and surface normal
};

class Renderer {
 public:
  Renderer(const Scene& scene, const PinholeCamera& camera, double near_m = 0.05);

  // Renders with the session's radiance (PrepareSessionRadiance): the quads,
  // then the meshes' triangles into the same depth buffer (both sides drawn:
  // catalog models have open, one-sided parts), each mesh pixel shaded with
  // its material's mip-mapped texture times the vertex light interpolated
  // perspective-correctly (with radiance.mesh_sun, the sun per pixel over the
  // triangles it samples). Mirrors reflect the quads only.
  void Render(const SessionRadiance& radiance, const Rigid3d& world_from_camera,
              RenderedView* view) const;
  // Renders a scene without meshes with `radiance` from PrepareRadiance (one
  // texture per quad).
  void Render(const std::vector<cv::Mat>& radiance, const Rigid3d& world_from_camera,
              RenderedView* view) const;

  const PinholeCamera& camera() const { return camera_; }

 private:
  struct QuadSetup;
  // Where a mirror pass may write: the pixels of quad `mirror` in `ids`,
  // and only fragments farther than its depth there.
  struct MirrorMask {
    const cv::Mat* ids = nullptr;
    const cv::Mat* depth_m = nullptr;
    int mirror = -1;
  };
  // `mirrored`: q is the mirror image of a scene quad, whose visible side
  // faces away from the camera (winding reversed).
  bool SetupQuad(const Quad& q, int index, const Rigid3d& camera_from_world, bool mirrored,
                 QuadSetup* setup) const;
  void RasterizeDepth(const QuadSetup& setup, cv::Mat* inv_depth, cv::Mat* ids,
                      const MirrorMask* mask = nullptr) const;
  // `window_view`: what the windows show by viewing direction (null or
  // disabled: their textures as they are).
  // `meshes`: the session's mesh light (null: a scene without meshes).
  void RenderScene(const std::vector<cv::Mat>& radiance, const SessionRadiance* meshes,
                   const WindowViewRadiance* window_view,
                   const Rigid3d& world_from_camera, RenderedView* view) const;
  // Draws the meshes' triangles into view->depth_m (inverse depth, the
  // quads' already there), marks their pixels in view->surface_id and
  // shades them into view->radiance, view->cos_incidence.
  void RenderMeshes(const SessionRadiance& radiance, const Rigid3d& camera_from_world,
                    RenderedView* view) const;
  // Blends the room reflected in mirror quad `mirror` into view->radiance.
  void AddReflection(int mirror, const std::vector<cv::Mat>& radiance,
                     const Rigid3d& camera_from_world, RenderedView* view) const;

  const Scene& scene_;
  PinholeCamera camera_;
  double near_m_;
  bool has_mirrors_ = false;
};

}  // namespace duskmap

// The scene as the renderer reads it: plain structs, all geometry already in world space.
// Loaders (io) fill it; the accelerator (accel) and shading (render) read it.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "parallax/core/math.h"
#include "parallax/core/transform.h"
#include "parallax/image/image.h"
#include "parallax/scene/gaussians.h"
#include "parallax/scene/look.h"

namespace parallax {

// A texture is either a constant, a checkerboard, or an image looked up through mesh UVs.
struct Texture {
  enum class Kind { Constant, Checker, Image };
  Kind kind = Kind::Constant;
  Vec3f color{0.8f};         // Constant; the first checker colour
  Vec3f color2{0.2f};        // the second checker colour
  float checkerSize = 1.0f;  // Checker: edge of one square, in world units
  int image = -1;            // Image: index into Scene::images
};

struct Material {
  std::string name;
  Vec3f diffuse{0.8f};      // albedo (linear), multiplied with the texture if there is one
  int diffuseTexture = -1;  // index into Scene::textures, or -1
  Vec3f mirror{0.0f};       // perfect specular reflectance; the diffuse part gets the rest
  Vec3f emission{0.0f};     // emitted radiance (linear); emissive meshes become area lights
};

// A triangle mesh in world space with one material. Normals and UVs are per vertex and
// optional (empty, or the same size as `positions`).
struct TriangleMesh {
  std::string name;
  uint32_t material = 0;
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;
  std::vector<Vec2f> uvs;
  // Vertex colours (linear RGB), multiplied into the material's diffuse albedo and
  // interpolated with the barycentrics (docs/gltf.md, "Vertex colours"); empty or one per
  // position.
  std::vector<Vec3f> colors;
  std::vector<uint32_t> indices;  // three per triangle

  size_t triangleCount() const { return indices.size() / 3; }
};

struct Sphere {
  std::string name;
  uint32_t material = 0;
  Vec3f center;
  float radius = 1.0f;
};

struct Light {
  enum class Kind { Point, Directional, Quad, Mesh, Spot };
  Kind kind = Kind::Point;
  // Point/Spot: W/sr per channel (on the axis for Spot); Directional: irradiance; Quad/Mesh:
  // radiance.
  Vec3f intensity{1.0f};
  Vec3f position;             // Point, Spot
  Vec3f direction{0, -1, 0};  // Directional: the direction light travels; Spot: its axis (unit)
  // Spot: full intensity within innerCone of the axis, none beyond outerCone (radians), with
  // KHR_lights_punctual's smooth falloff between (spotAttenuation, render/light_sampler.h).
  float innerCone = 0.0f, outerCone = 0.7853982f;
  Vec3f corner, edgeU, edgeV;  // Quad: emits from the side of cross(edgeU, edgeV)
  bool twoSided = false;       // Quad/Mesh: emit from both faces
  int mesh = -1;               // Mesh: index into Scene::meshes (its material's emission)
  int samples = 1;             // shadow rays per shading point for area lights
};

// How the content is framed for the display (docs/display-geometry.md, "Depth budget"):
// Window: the width fitted so that the content's bounds fill the window (the width-only fit);
// Depth: the window fit with the zero-parallax plane inside the content and the depth
// compressed (the camera's virtual gap) into the depth budget; Camera: the window is what the
// scene's file camera (a Blender shot) sees at its focus distance, the zero-parallax plane
// there, the depth compressed as for Depth; None: the display block as it is. Auto: Camera for
// a file camera's shot without a display width, Depth without a width, None with one.
enum class DisplayFit { Auto, Window, Depth, None, Camera };

// A file camera's shot (docs/gltf.md, "Framing a shot"): where the camera is, its fields of
// view and the distance along its line of sight that the display's window frames (the focus
// distance). The placement's centre is eye + forward * focusDistance.
struct ShotFrame {
  Vec3f eye;
  float yfovRadians = 0;
  float aspectRatio = 0;  // width / height from the file; 0: not given (the display's)
  float focusDistance = 0;
  std::string focusSource;  // how the focus distance was chosen, for the summary line
};

// Ranges of the framing's millimetres: the focus offset within +-kMaxFocusMm, the depth budget
// above 0 and up to kMaxDepthBudgetMm.
inline constexpr double kMaxFocusMm = 1e4, kMaxDepthBudgetMm = 1000;

// Where the physical display sits in the scene. The display's width (in mm, from the display
// description) maps onto `width` scene units; `normal` points from the display toward the
// viewer, `up` is the display's +y. Scene content on the viewer's side of the plane appears in
// front of the display (pops out), content behind it appears behind the screen.
struct DisplayPlacement {
  Vec3f center{0.0f};
  Vec3f normal{0, 0, 1};
  Vec3f up{0, 1, 0};
  float width = 1.0f;
  // Set when the scene gives no width: these bounds should be seen whole through the window,
  // so `width` is fitted to each display (fitDisplayWidth in camera/display_camera.h).
  std::optional<Bounds3f> fit;
  // The framing (camera/framing.h): the mode, the zero-parallax plane's offset from `center`
  // in display mm toward the viewer (unset: auto, inside the content), and the depth budget,
  // half the displayed depth range in mm (unset: the display's depth of field, G4).
  DisplayFit fitMode = DisplayFit::Auto;
  std::optional<double> focusMm;
  std::optional<double> depthBudgetMm;
  // The objects' bounds (what the framing measures), whether or not a width is given; unset:
  // the whole scene's bounds.
  std::optional<Bounds3f> content;
  // Points whose hull holds the content, when its box is a poor fit (an RGB-D photo is a
  // frustum: its box's near corners are as wide as its far end). The Depth and Window fits
  // (with a focus) then fit these instead of the box's corners; the depth range stays the box's.
  std::vector<Vec3f> contentHull;
  // The file camera whose shot the window frames (set by --camera and a bare glTF file's
  // first camera; DisplayFit::Camera).
  std::optional<ShotFrame> shot;
  // The content is a picture that should fill the window (an RGB-D photo, whose hull is the
  // frustum between its nearest and farthest depth): the Depth fit then covers the window, so
  // that every ray of the display from the window meets the content, instead of fitting the
  // content inside it (camera/framing.h).
  bool fillWindow = false;
};

// An ordinary pinhole camera for `parallax view`.
struct CameraSpec {
  Vec3f eye{0, 0, 5};
  Vec3f lookAt{0.0f};
  Vec3f up{0, 1, 0};
  float fovDegrees = 40.0f;  // vertical field of view
};

// Keys of a scene file's animation (docs/animation.md): at `seconds`, the view camera or the
// display placement; between keys both are interpolated (scene/motion.h).
struct CameraKey {
  double seconds = 0;
  CameraSpec camera;
};
struct DisplayKey {
  double seconds = 0;
  Vec3f center{0.0f};
  Vec3f normal{0, 0, 1};
  Vec3f up{0, 1, 0};
};

// A glTF file's node animation (docs/animation.md): its node tree with keyed translation,
// rotation and scale channels, and the scene meshes that hang from animated nodes. Each such
// mesh is stored posed at rest (the nodes' own TRS); scene/motion.h moves it.
struct NodeChannel {
  enum class Path { Translation, Rotation, Scale };
  Path path = Path::Translation;
  bool step = false;                         // STEP: hold each key; otherwise LINEAR
  std::vector<float> times;                  // seconds, increasing
  std::vector<std::array<float, 4>> values;  // xyz (w unused), or a quaternion xyzw
};
struct AnimatedNode {
  int parent = -1;
  Vec3f translation{0.0f};
  std::array<float, 4> rotation{0, 0, 0, 1};  // unit quaternion xyzw
  Vec3f scale{1.0f};
  std::optional<Mat4> matrix;  // a node given by its matrix (not animatable in glTF)
  std::vector<NodeChannel> channels;
};
struct AnimatedMesh {
  uint32_t mesh = 0;       // index into Scene::meshes
  int node = -1;           // index into NodeAnimation::nodes
  Mat4 worldFromFile;      // the load's transform on top of the file's nodes
  Mat4 restMeshFromWorld;  // undoes the rest pose: (worldFromFile * fileFromNode(rest))^-1
};
struct NodeAnimation {
  std::vector<AnimatedNode> nodes;
  std::vector<AnimatedMesh> meshes;
  double seconds = 0;  // the last key's time
  bool empty() const { return meshes.empty(); }
};

// A camera a mesh file brings (glTF), in world space; `parallax view` and `render` use the
// chosen one (--camera, docs/gltf.md).
struct NamedCamera {
  std::string name;       // the camera's name, else its node's, else "camera N"
  std::string nodeName;   // its node's name (Blender's object name, as the outliner shows it)
  std::string source;     // the file
  CameraSpec spec;        // eye, a point on the line of sight, up, vertical field of view
  float aspectRatio = 0;  // width / height from the file; 0: not given
  float znear = 0;        // the near plane from the file (informational: we do not clip)
  int note = -1;          // index of the file's line in Scene::notes, or -1
};

// An object of a loaded file by its node's name (glTF; Blender's object name): its world
// bounds, the union over every node of that name (--focus-on, docs/gltf.md).
struct NamedObject {
  std::string name;
  std::string source;  // the file
  Bounds3f bounds;
};

struct Scene {
  std::string source;  // file it came from, or "<built-in>"
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Image> images;  // linear RGB texture images
  std::vector<Light> lights;
  std::vector<SplatSet> splats;
  Vec3f ambient{0.0f};     // uniform ambient radiance reaching every surface (unshadowed)
  Vec3f background{0.0f};  // radiance of rays that escape
  Look look;               // exposure and view transform of every picture (look.h)
  int maxDepth = 4;        // mirror bounces
  DisplayPlacement display;
  std::optional<CameraSpec> camera;
  std::vector<CameraKey> cameraKeys;    // sorted by time; empty: the camera does not move
  std::vector<DisplayKey> displayKeys;  // sorted by time; empty: the display does not move
  NodeAnimation nodeAnimation;          // glTF node animation; empty: nothing animated
  std::vector<NamedCamera> cameras;     // cameras of the loaded files, in file order
  std::vector<NamedObject> objects;     // named nodes of the loaded files, in file order
  std::vector<std::string> warnings;
  // What was taken from and ignored in each loaded file (one line per glTF file; docs/gltf.md).
  std::vector<std::string> notes;
  // What loading each mesh file did (importer/mesh_file.h, docs/import.md); written to render.json.
  struct ImportRecord {
    std::string file;
    std::string
        reader;      // "parallax-obj", "parallax-ply", "parallax-stl", "parallax-gltf", "assimp"
    std::string up;  // the file's up axis as used: "y" or "z"
    std::string normals;  // "file", "generated (crease 60°)", "faceted", or a mix joined by " + "
    size_t triangles = 0;
    size_t splats = 0;  // Gaussian splats (a splat file has no triangles)
  };
  std::vector<ImportRecord> imports;

  size_t triangleCount() const;
  size_t splatCount() const;
  // Meshes, spheres and the splats' centres.
  Bounds3f bounds() const;
  // What a framing fits: the same, with each splat set's framing bounds (splatFramingBounds)
  // for its centres.
  Bounds3f framingBounds() const;
};

// The distance along the ray origin + t direction (t > 0, in units of |direction| = 1) to the
// first triangle (either face) or sphere it meets, by brute force over every primitive (one
// ray: the focus of a file camera's shot); nullopt when it meets nothing.
std::optional<float> firstHitDistance(const Scene& scene, const Vec3f& origin,
                                      const Vec3f& direction);

// Appends an axis-aligned box [lo, hi] as a 12-triangle mesh, outward facing.
void addBox(Scene& scene, const std::string& name, const Vec3f& lo, const Vec3f& hi,
            uint32_t material);
// Appends a parallelogram corner + s*edgeU + t*edgeV, s,t in [0,1], as two triangles with UVs
// (s, t); its front face is the side of cross(edgeU, edgeV).
void addQuad(Scene& scene, const std::string& name, const Vec3f& corner, const Vec3f& edgeU,
             const Vec3f& edgeV, uint32_t material);

// The paper's scene: a box levitating above a checkerboard floor, lit so that it casts a
// clearly visible soft shadow, placed in front of a display of width 1 scene unit per 100 mm.
Scene defaultScene();

// A camera that frames the whole scene from the viewer's side of the display.
CameraSpec frameScene(const Scene& scene, float fovDegrees = 40.0f);

}  // namespace parallax

#pragma once
// The stability suite: every screen-space method fails somewhere; this says
// where, in numbers, and checks that it fails gracefully.
//
// stability_scenes.cpp builds the scenes in code; stability_cases.cpp has one
// function per failure mode that renders (and, where the case compares with
// truth, traces the Embree reference) and returns a CaseResult: the measured
// numbers, each asserted one with its bound, and the pictures. The doctest
// suite (tests/stability_tests.cpp) asserts the checks; stability-report runs
// the same functions and writes docs/STABILITY.md's table and pictures.
#include <string>
#include <vector>

#include "headlight/frame.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene.hpp"
#include "headlight/settings.hpp"
#include "scene/builtin_layouts.hpp"

namespace headlight::stability {

// ---- Scenes (stability_scenes.cpp) --------------------------------------------

// Geometry comes from headlight/shapes.hpp, assembly from
// headlight/scene_builder.hpp.

// Case 1: a 100 x 100 floor seen from 2 units up; nothing can occlude it.
Scene flatPlaneScene();
// Case 2: the Cornell box with its camera 0.1 from the back wall (inside the
// SSGI radius, 0.52), looking into the corner with the floor and red wall.
Scene nearWallScene();
// Case 3: nine slats 0.04 wide, 0.12 in front of a wall.
Scene slatsScene();
using SlatLayout = builtin::SlatLayout;
// Case 4: a floor and a tall box cut by the left image border.
Scene offscreenBoxScene();
// Case 5: a sphere 1.4..2.6 units in front of a wall (1.05..1.9 SSGI radii).
Scene depthStepScene();
using DepthStepLayout = builtin::DepthStepLayout;
// Case 6: a 1000 x 1000 floor, camera half a unit up, looking at the horizon.
Scene grazingFloorScene();
// Case 6: `scene` with every instance, camera and light scaled about the
// origin by `scale` (point-light intensity by scale^2, so lit stays the same).
Scene scaledScene(Scene scene, float scale);
// Case 9: the Cornell camera orbited by `degrees` about the box's vertical axis.
Camera cornellOrbitCamera(float degrees);

// Case 7: degenerate input.
Scene nanVertexScene();       // a good floor plus a triangle with a NaN vertex, built in code
Scene zeroAreaScene();        // a quad plus point and collinear triangles, normals from generateNormals
Scene missingNormalsScene();  // a box whose normals come from generateNormals (it had none)
Scene hugeCoordinateScene();  // a floor reaching 1e20 and a unit box on it
Scene emptyScene();           // no instances at all
// A one-quad glTF (non-indexed, no normals: the loader generates them) with
// its buffer as a data URI; `nanPosition` puts a NaN in the first vertex.
std::string quadGltfJson(bool nanPosition);

// ---- Results (stability_cases.cpp) ----------------------------------------------

enum class Relation { AtLeast, AtMost };

// A measured number and the bound the suite asserts on it. A check with a
// known bug is expected to fail: the test asserts that it still does, so the
// fix (which makes it pass) also has to clear `knownBug` and promote it.
struct Check {
  std::string quantity;  // what was measured, e.g. "min AO, interior pixels"
  double measured = 0;
  Relation relation = Relation::AtMost;
  double bound = 0;
  std::string knownBug;  // empty, or the file and cause of the failure (docs/STABILITY.md "Bugs found")
  bool holds() const { return relation == Relation::AtLeast ? measured >= bound : measured <= bound; }
};

// A measured number that is reported, not asserted.
struct Note {
  std::string quantity;
  double value = 0;
};

// One picture in a case's strip: a channel as grey (0..1), an RGB image
// tonemapped, or a signed error as blue (negative) to red (positive).
struct Panel {
  enum class Kind { Grey, Tonemapped, Signed };
  std::string label;
  ImageF image;
  int channel = 0;  // first channel shown
  Kind kind = Kind::Grey;
  float scale = 1;  // Signed: the error shown at full colour
  ImageF coverage;  // optional: a frame's position target; background (A = 0) is shown as sky blue
};

struct CaseResult {
  std::string id;           // picture file stem, e.g. "flat-plane"
  std::string failureMode;  // the table row, e.g. "Flat open plane (false occlusion)"
  std::string method;       // "hemisphere" or "radiance"
  std::vector<Check> checks;
  std::vector<Note> notes;
  std::vector<Panel> panels;

  // Every check and note, one per line (test failure messages, --verbose).
  std::string describe() const;
};

// Reference traces in this suite: 256 rays per pixel keeps a trace of a
// 128 x 96 frame well under a second on 2 cores; the AO standard error at
// that count is about 0.02 per pixel, well below the errors measured.
constexpr int kReferenceSamples = 256;

// One function per failure mode; each sets the renderer's scene.
CaseResult flatOpenPlane(Renderer& renderer, SsgiMethod method);
CaseResult cameraInsideRadius(Renderer& renderer, SsgiMethod method);
CaseResult thinGeometry(Renderer& renderer, SsgiMethod method);
CaseResult screenEdge(Renderer& renderer, SsgiMethod method);
CaseResult depthDiscontinuity(Renderer& renderer, SsgiMethod method);
CaseResult grazingFloor(Renderer& renderer, SsgiMethod method);
CaseResult sceneScale(Renderer& renderer, SsgiMethod method);
CaseResult degenerateInput(Renderer& renderer, SsgiMethod method);
CaseResult resolutionEdges(Renderer& renderer, SsgiMethod method);
CaseResult flicker(Renderer& renderer, SsgiMethod method);

using CaseFunction = CaseResult (*)(Renderer&, SsgiMethod);
struct CaseEntry {
  const char* name;
  CaseFunction run;
  bool needsReference;
};
// Every case in the order of docs/STABILITY.md.
const std::vector<CaseEntry>& allCases();
constexpr SsgiMethod kMethods[] = {SsgiMethod::Hemisphere, SsgiMethod::Radiance, SsgiMethod::Bitmask};

// Count of NaN or infinite floats over every target of `frame`.
long long nonFiniteCount(const Frame& frame);

}  // namespace headlight::stability

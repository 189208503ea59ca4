// The camera of a set of photos from the shot's ring of markers: each photo's markers found and
// matched to where the ring puts them on the front of the display, then one camera (focal length
// and radial distortion) and a pose per photo fitted to them all. Both estimators start here.
#pragma once

#include <string>
#include <vector>

#include "parallax/photocal/shot_layout.h"
#include "parallax/vision/vision.h"

namespace parallax::photocal {

// A decoded photo and the name it is refused under (its file name).
struct NamedPhoto {
  std::string name;
  vision::Photo photo;
};

struct MarkerCamera {
  vision::CameraFit fit;
  std::vector<std::vector<vision::PlaneCorrespondence>> markerPoints;  // per photo
  std::vector<int> markersFound;                                       // per photo, of the ring's
  double focalRelativeSigma = 0;  // the focal length's sigma over itself
};

// Throws InputError(photo name, "", why) for a photo with fewer than minMarkers of the ring
// (naming the shot, and saying so when the photo shows another shot's markers).
MarkerCamera markerCamera(const MarkerRing& ring, const PanelGrid& front,
                          const std::string& shotName, const std::vector<NamedPhoto>& photos,
                          int minMarkers);

// Fits the camera again to the markers and, per photo, more points of the panel plane.
void refitCamera(MarkerCamera& camera, const std::vector<NamedPhoto>& photos,
                 const std::vector<std::vector<vision::PlaneCorrespondence>>& more);

// The camera's centre for photo i (display frame, mm); throws InputError naming the photo when
// it is not in front of the display.
std::array<double, 3> cameraCentre(const MarkerCamera& camera, size_t photo,
                                   const std::string& name);

}  // namespace parallax::photocal

#include "parallax/photocal/marker_camera.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "parallax/core/error.h"

namespace parallax::photocal {

namespace {

std::string markerCount(int found, size_t of) {
  return std::to_string(found) + " of its " + std::to_string(of) + " markers";
}

}  // namespace

MarkerCamera markerCamera(const MarkerRing& ring, const PanelGrid& front,
                          const std::string& shotName, const std::vector<NamedPhoto>& photos,
                          int minMarkers) {
  std::map<int, const MarkerRing::Placement*> byId;
  for (const auto& m : ring.markers) byId[m.id] = &m;
  std::vector<std::vector<vision::PlaneCorrespondence>> views;
  std::vector<std::string> names;
  MarkerCamera camera;
  for (const NamedPhoto& p : photos) {
    std::vector<vision::PlaneCorrespondence> view;
    int ours = 0, others = 0;
    for (const vision::DetectedMarker& d : vision::detectMarkers(p.photo)) {
      const auto it = byId.find(d.id);
      if (it == byId.end()) {
        ++others;
        continue;
      }
      ++ours;
      const auto corners = ring.cornersPx(*it->second);
      for (size_t c = 0; c < 4; ++c)
        view.push_back({front.xMm(corners[c][0]), front.yMm(corners[c][1]), d.corners[c]});
    }
    if (ours < minMarkers)
      throw InputError(p.name, "",
                       others > ours && others >= minMarkers
                           ? "shows another shot's markers, not shot " + shotName + "'s (" +
                                 markerCount(ours, ring.markers.size()) + " found)"
                           : "the panel was not found: " + markerCount(ours, ring.markers.size()) +
                                 " of shot " + shotName +
                                 " seen (the whole panel must be in the photo, in focus)");
    views.push_back(std::move(view));
    names.push_back(p.name);
    camera.markersFound.push_back(ours);
  }
  // A marker misread (a moire band or noise through its cells can turn one into another id)
  // pulls the whole fit: the worst marker, when it is far off the others' camera, is dropped
  // and the camera fitted again.
  for (int round = 0; round < 64; ++round) {
    camera.fit = vision::fitCamera(views, names, photos[0].photo.width, photos[0].photo.height);
    double worst = 0;
    size_t worstPhoto = 0, worstMarker = 0;
    for (size_t i = 0; i < views.size(); ++i) {
      if (views[i].size() / 4 <= size_t(minMarkers)) continue;
      std::vector<double> errors;
      for (size_t m = 0; m < views[i].size() / 4; ++m) {
        double sum = 0;
        for (size_t c = 0; c < 4; ++c) {
          const vision::PlaneCorrespondence& q = views[i][4 * m + c];
          const vision::PhotoPoint p =
              vision::projectPoint(camera.fit.intrinsics, camera.fit.poses[i], {q.xMm, q.yMm, 0});
          sum += std::hypot(p.x - q.photo.x, p.y - q.photo.y);
        }
        errors.push_back(sum / 4);
      }
      std::vector<double> sorted = errors;
      std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
      const double median = sorted[sorted.size() / 2];
      for (size_t m = 0; m < errors.size(); ++m)
        if (errors[m] > std::max(4.0, 4 * median) && errors[m] > worst)
          worst = errors[m], worstPhoto = i, worstMarker = m;
    }
    if (worst == 0) break;
    auto& view = views[worstPhoto];
    view.erase(view.begin() + long(4 * worstMarker), view.begin() + long(4 * worstMarker + 4));
    --camera.markersFound[worstPhoto];
  }
  camera.markerPoints = views;
  camera.focalRelativeSigma = camera.fit.focalSigmaPx / camera.fit.intrinsics.focalPx;
  return camera;
}

void refitCamera(MarkerCamera& camera, const std::vector<NamedPhoto>& photos,
                 const std::vector<std::vector<vision::PlaneCorrespondence>>& more) {
  // The markers' corners only where the other points are too few: their corners are found to
  // about a photo pixel, the gratings' points to a twentieth of one.
  std::vector<std::vector<vision::PlaneCorrespondence>> views(photos.size());
  std::vector<std::string> names;
  for (size_t i = 0; i < photos.size(); ++i) {
    views[i] = more[i].size() >= 24 ? more[i] : camera.markerPoints[i];
    if (more[i].size() < 24) views[i].insert(views[i].end(), more[i].begin(), more[i].end());
    names.push_back(photos[i].name);
  }
  // Twice: the second time without the points more than three times the median error off
  // (a block the moire darkened, or one whose phase slipped a period).
  for (int pass = 0; pass < 2; ++pass) {
    camera.fit = vision::fitCamera(views, names, photos[0].photo.width, photos[0].photo.height);
    if (pass == 1) break;
    for (size_t i = 0; i < views.size(); ++i) {
      std::vector<double> errors;
      for (const auto& c : views[i]) {
        const vision::PhotoPoint p =
            vision::projectPoint(camera.fit.intrinsics, camera.fit.poses[i], {c.xMm, c.yMm, 0});
        errors.push_back(std::hypot(p.x - c.photo.x, p.y - c.photo.y));
      }
      std::vector<double> sorted = errors;
      std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
      const double limit = std::max(3 * sorted[sorted.size() / 2], 0.05);
      std::vector<vision::PlaneCorrespondence> kept;
      for (size_t k = 0; k < views[i].size(); ++k)
        if (errors[k] <= limit) kept.push_back(views[i][k]);
      if (kept.size() >= 8) views[i] = std::move(kept);
    }
  }
  camera.focalRelativeSigma = camera.fit.focalSigmaPx / camera.fit.intrinsics.focalPx;
}

std::array<double, 3> cameraCentre(const MarkerCamera& camera, size_t photo,
                                   const std::string& name) {
  const std::array<double, 3> c = camera.fit.poses[photo].cameraCentre();
  if (!(c[2] > 0))
    throw InputError(name, "", "the camera is behind the display (a mirrored photo?)");
  return c;
}

}  // namespace parallax::photocal

// RGB-D photos from files (docs/rgbd.md): a colour image and a greyscale depth map of the same
// size become the displaced height-field scene of scene/rgbd.h.
#pragma once

#include <string>

#include "parallax/scene/rgbd.h"
#include "parallax/scene/scene.h"

namespace parallax {

// Reads the two files and builds the scene. The colour image: any image readImage reads (sRGB
// decoded to linear, alpha dropped). The depth map: its samples as stored (no transfer
// function), 8- or 16-bit (a 16-bit PNG keeps its 16 bits), or PFM floats in [0, 1]; one
// channel (grey, grey + alpha), or RGB(A) whose three channels are equal in every pixel (a grey
// picture saved as colour). A map with different channels is refused rather than read by its
// first channel: it is most likely a colour-mapped picture of depth, whose channels are not
// the depth. Throws InputError naming the file: missing or unreadable files, sizes that differ
// (both sizes), a coloured depth map, float values outside [0, 1], and photos whose scene would
// need more than `memoryLimitBytes` (0: 3/4 of physical memory), estimated from the depth map's
// header size before the colour image and the mesh are allocated. A constant depth map is a
// warning (scene.warnings): the photo is then flat.
Scene loadRgbdScene(const std::string& colourPath, const std::string& depthPath,
                    const RgbdOptions& options, double memoryLimitBytes = 0);

}  // namespace parallax

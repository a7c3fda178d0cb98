// `trackbed image-stats DIR [DIR ...] [--every N] [--first N] [--count N] [--bands N]
// [--json FILE] [--csv FILE]`: image statistics per band of rows over folders of images
// (docs/image_statistics.md): FAST and Shi–Tomasi corners, mean gradient, the power
// spectrum's slope, grey-level mean and standard deviation, and the share of FAST
// corners Lucas–Kanade tracks into the next image.
//
// DIR: a run folder (its images/image_0/, saved with outputs.save_images: kitti), a
// KITTI-layout sequence (its image_0/) or a folder of PNG images
// (perception/trackbed/perception/image_sequence_statistics.h). Of each folder's images
// in file-name order, images first, first + every, … are measured, at most count (0:
// all); the figures are the means over them.
//
// Prints one table per statistic, one row per folder and one column per band (top to
// bottom). --json FILE: the options, and per folder its images and size and each band's
// rows and figures (a figure that is undefined, null). --csv FILE: one line per folder and
// band: `folder,band,row_begin,row_end,images,fast_corners,shi_tomasi_corners,
// mean_gradient,spectrum_slope,grey_mean,grey_std,track_share` (undefined: empty).
#pragma once

#include <CLI/CLI.hpp>

namespace trackbed::apps {

/// Registers the `image-stats` subcommand (exit 0 when measured and written; 2, after a
/// one-line reason on stderr, for a folder without images, an unreadable image, images
/// of different sizes or a bad option); like AddVoCommand it ends parsing by throwing
/// (CLI::Success or CLI::RuntimeError).
void AddImageStatsCommand(CLI::App& app);

}  // namespace trackbed::apps

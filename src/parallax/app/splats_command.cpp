// `parallax splats`: Gaussian splat files made for testing and showing (docs/splats.md, "Making
// splat files"), over jobs::runSplatMaking.
#include <memory>

#include "parallax/app/commands.h"
#include "parallax/jobs/splat_making.h"

namespace parallax::app {

namespace {

void addMakingOptions(Command& cmd, jobs::SplatMakingRequest& request, const char* countHelp) {
  cmd.addOption("-o,--output", request.output, "The splat file to write (.ply, 3DGS's layout)")
      ->required();
  cmd.addOption("--count", request.count, countHelp)
      ->check(integerIn(1, int64_t(jobs::kMaxMadeSplats)));
  cmd.addOption("--seed", request.seed, "Seed of the random placement")
      ->captureDefault()
      ->check(seedValue());
  addLimitOptions(cmd);
}

}  // namespace

void registerSplatsCommand(Command& cli) {
  Command* splats = cli.addSubcommand("splats", "Make Gaussian splat files (docs/splats.md)");
  splats->requireSubcommand(1);

  auto fromMesh = std::make_shared<jobs::SplatMakingRequest>();
  fromMesh->source = jobs::SplatMakingRequest::Source::Surfaces;
  Command* mesh = splats->addSubcommand(
      "from-mesh", "Cover a scene's surfaces with flat Gaussians coloured by its albedo, lit");
  mesh->addOption("scene", fromMesh->scene.path,
                  "Scene or mesh file (the built-in scene if omitted)");
  addImportOptions(*mesh);
  addMakingOptions(*mesh, *fromMesh, "Gaussians over all the triangles, by area (default 200000)");
  mesh->callback([fromMesh] {
    fromMesh->scene.load.import = importOptions();
    jobs::runSplatMaking(*fromMesh, cliReporter());
  });

  auto capture = std::make_shared<jobs::SplatMakingRequest>();
  Command* like = splats->addSubcommand(
      "capture-like",
      "A capture-like cloud: many small, semi-transparent, view-dependent Gaussians");
  addMakingOptions(*like, *capture, "Gaussians (default 1000000)");
  like->callback([capture] { jobs::runSplatMaking(*capture, cliReporter()); });
}

}  // namespace parallax::app

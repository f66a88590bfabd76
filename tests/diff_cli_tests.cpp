// headlight diff from the command line (runDiffCommand, called directly):
// folder mode, --out, default thresholds per target, usage errors and
// exit codes, and the metric each target is judged by (FLIP for lit).
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "color/srgb.hpp"
#include "diff/flip.hpp"
#include "diff_command.hpp"
#include "diff_test_images.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
namespace fs = std::filesystem;
using namespace headlight::test;

TEST_CASE("diff: folder mode reports each target and the worst verdict" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_folders");
  const fs::path a = folder / "a", b = folder / "b";
  fs::create_directories(a);
  fs::create_directories(b);
  TestImage depth = gradient(10, 10, {"depth.Z"});
  depth.far = 5;
  const TestImage albedo = gradient(10, 10, {"albedo.B", "albedo.G", "albedo.R"});
  const TestImage lit = gradient(10, 10, {"A", "B", "G", "R"});
  for (const fs::path& dir : {a, b}) {
    write(dir / "depth.exr", depth);
    write(dir / "lit.exr", lit);
  }
  write(a / "albedo.exr", albedo);
  TestImage changed = albedo;
  for (int x = 0; x < 10; ++x) changed.at(x, 4, 2) += 0.2f;
  write(b / "albedo.exr", changed);
  write(a / "notes.exr", albedo);  // not a target: ignored

  const DirectoryDiff result = diffDirectories(a, b);
  CHECK(result.status == DiffStatus::Fail);
  REQUIRE(result.targets.size() == 3);
  CHECK(result.targets[0].target == "albedo");
  CHECK(result.targets[0].status == DiffStatus::Fail);
  CHECK(result.targets[1].target == "depth");
  CHECK(result.targets[1].status == DiffStatus::Pass);
  CHECK(result.targets[2].status == DiffStatus::Pass);

  const fs::path out = folder / "diffs";
  Cli cli = runCli({a.string(), b.string(), "--out", out.string()});
  INFO(cli.out, cli.err);
  CHECK(cli.exitCode == 2);
  CHECK(contains(cli.out, "albedo    FAIL"));
  CHECK(contains(cli.out, "depth     PASS"));
  CHECK(contains(cli.out, "verdict: FAIL (3 targets: 2 pass, 0 warn, 1 fail"));
  CHECK(fs::exists(out / "albedo_diff.exr"));
  CHECK(fs::exists(out / "albedo_diff.png"));
  CHECK(fs::exists(out / "lit_diff.exr"));
  CHECK(fs::exists(out / "lit_diff_a.png"));  // lit is judged by FLIP: its images beside the map
  std::ifstream report(out / "report.html");
  const std::string page((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  CHECK(contains(page, "albedo_diff.png"));
  CHECK(contains(page, "lit_diff_b.png"));
  CHECK(contains(page, "<span class='fail'>FAIL</span>"));
  // One self-contained page: the verdict and exit code first, every image
  // inside it (a PNG's base64 starts with its signature's, iVBORw0KGgo), no
  // image linked by name, and each map's colour scale labelled.
  CHECK(contains(page, "<p class='verdict fail'>verdict: FAIL (3 targets: 2 pass, 0 warn, 1 fail"));
  CHECK(contains(page, " &mdash; exit 2</p>"));
  CHECK(page.find("verdict") < page.find("<table>"));
  CHECK(contains(page, "src='data:image/png;base64,iVBORw0KGgo"));
  CHECK_FALSE(contains(page, "src='albedo"));
  CHECK_FALSE(contains(page, "src='lit"));
  CHECK(fs::exists(out / "albedo_diff_scale.png"));
  CHECK(contains(page, "alt='albedo_diff_scale.png'"));
  CHECK(contains(page, "<span>fail 0.01</span><span>0.02 or more</span>"));  // albedo: fail mid-scale
  CHECK(contains(page, "<span>1 (FLIP)</span>"));                            // lit: FLIP's 0..1
  {
    // The embedded heatmap is the file's bytes: its base64 is 4 characters per 3 bytes.
    const auto at = page.find("alt='albedo_diff.png' src='data:image/png;base64,");
    REQUIRE(at != std::string::npos);
    const auto start = page.find("base64,", at) + 7, end = page.find('\'', start);
    CHECK(end - start == (fs::file_size(out / "albedo_diff.png") + 2) / 3 * 4);
  }

  // A target in one folder only is structural, and the worst status wins.
  write(b / "ssgi.exr", gradient(10, 10, {"ao.Y"}));
  cli = runCli({a.string(), b.string()});
  CHECK(cli.exitCode == 3);
  CHECK(contains(cli.out, "ssgi      STRUCTURAL"));
  CHECK(contains(cli.out, "ssgi.exr is in " + b.string() + " only"));

  // Folders with no target, a missing folder, a folder against a file.
  fs::create_directories(folder / "empty");
  CHECK(runCli({(folder / "empty").string(), (folder / "empty").string()}).exitCode == 4);
  CHECK(runCli({a.string(), (folder / "nowhere").string()}).exitCode == 4);
  CHECK(runCli({a.string(), (a / "lit.exr").string()}).exitCode == 5);
  CHECK(runCli({a.string(), b.string(), "--channels", "R"}).exitCode == 5);
  fs::remove_all(folder);
}

TEST_CASE("diff: --out writes a float diff.exr and a diff.png heatmap, atomically" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_out");
  const TestImage image = gradient(16, 16, {"R", "G", "B"});
  TestImage changed = image;
  changed.at(3, 3, 0) += 1.0f;
  write(folder / "lit.exr", image);
  write(folder / "changed.exr", changed);
  const fs::path exr = folder / "report" / "diff.exr";
  fs::create_directories(exr.parent_path());
  // lit's own metric is FLIP (below); --metric gives relative-to-value with
  // the first such row's thresholds (emissive's).
  const Cli cli = runCli({(folder / "lit.exr").string(), (folder / "changed.exr").string(), "--out", exr.string(),
                          "--metric", "relative-to-value"});
  INFO(cli.out, cli.err);
  CHECK(cli.exitCode == 1);  // one pixel of 256 over fail: within 0.5 %, so a warning
  CHECK(contains(cli.out, "wrote " + exr.string()));

  OIIO::ImageBuf diff(exr.string());
  REQUIRE(diff.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  CHECK(diff.spec().width == 16);
  CHECK(diff.spec().format == OIIO::TypeDesc::FLOAT);
  REQUIRE(diff.nchannels() == 4);
  CHECK(diff.spec().channelnames[3] == "error");
  const int red = diff.spec().channelindex("R"), error = diff.spec().channelindex("error");
  CHECK(diff.getchannel(3, 3, 0, red) == doctest::Approx(1.0));
  CHECK(diff.getchannel(3, 3, 0, error) ==
        doctest::Approx(1.0 / std::max(1.0, double(image.pixels[(3 * 16 + 3) * 3]))));
  CHECK(diff.getchannel(4, 3, 0, error) == 0);

  OIIO::ImageBuf png((folder / "report" / "diff.png").string());
  REQUIRE(png.read());
  CHECK(png.spec().format == OIIO::TypeDesc::UINT8);
  CHECK(png.nchannels() == 3);
  CHECK(png.spec().width == 16);
  // The changed pixel saturates the ramp (inferno's top is light); an
  // unchanged one is its dark bottom.
  CHECK(png.getchannel(3, 3, 0, 0) > 0.9f);
  CHECK(png.getchannel(4, 3, 0, 0) < 0.1f);
  // No temporary file left beside them.
  for (const auto& entry : fs::directory_iterator(exr.parent_path())) CHECK(entry.path().filename().string()[0] != '.');

  // Nothing to draw for a structural mismatch: the library says so, the CLI
  // reports the mismatch and writes nothing.
  write(folder / "small.exr", gradient(4, 4, {"R", "G", "B"}));
  const DiffResult mismatch = diffImages(folder / "lit.exr", folder / "small.exr");
  CHECK_THROWS_AS(writeDiffImages(mismatch, folder / "x.exr"), Error);
  CHECK(runCli({(folder / "lit.exr").string(), (folder / "small.exr").string(), "--out", (folder / "y.exr").string()})
            .exitCode == 3);
  CHECK(!fs::exists(folder / "y.exr"));
  // An unwritable destination is a file error (4) naming it.
  const Cli unwritable = runCli({(folder / "lit.exr").string(), (folder / "changed.exr").string(), "--out",
                                 (folder / "no" / "such" / "dir" / "d.exr").string()});
  CHECK(unwritable.exitCode == 4);
  CHECK(contains(unwritable.err, "d.exr"));
  fs::remove_all(folder);
}

TEST_CASE("diff: default thresholds by target, overridden by options" * doctest::test_suite("diff")) {
  CHECK(targetTolerance("normal").metric == DiffMetric::AngleDegrees);
  CHECK(targetTolerance("position").metric == DiffMetric::RelativeToScene);
  CHECK(targetTolerance("depth").metric == DiffMetric::RelativeToScene);
  CHECK(targetTolerance("lit").metric == DiffMetric::Flip);
  CHECK(targetTolerance("preview").metric == DiffMetric::Flip);
  CHECK(targetTolerance("emissive").metric == DiffMetric::RelativeToValue);
  CHECK(targetTolerance("albedo").metric == DiffMetric::Absolute);
  CHECK(targetTolerance("normal").thresholds.fail == 1.0);
  CHECK(targetTolerance("ssgi").thresholds.failPercent == 1.0);
  // Every target has a row with a reason, warn <= fail, and a finite mean
  // bound no looser than what its failPercent allowance could add at full scale.
  for (const FrameTarget& target : frameTargets()) {
    CAPTURE(target.name);
    const FrameTarget& row = targetTolerance(target.name);
    CHECK(row.name == target.name);
    CHECK(!row.reason.empty());
    CHECK(row.thresholds.warn <= row.thresholds.fail);
    CHECK(std::isfinite(row.thresholds.failMean));
  }
  // Anything else gets idiff's defaults.
  const DiffThresholds other = targetTolerance("golden_beauty").thresholds;
  CHECK(other.fail == 1e-6);
  CHECK(other.failPercent == 0);
  CHECK(std::isinf(other.hardFail));
  CHECK(std::isinf(other.failMean));
  CHECK(targetTolerance("golden_beauty").name.empty());

  DiffOptions options;
  options.fail = 0.5;
  options.hardWarn = 2;
  const DiffThresholds resolved = resolveThresholds("lit", options);
  CHECK(resolved.fail == 0.5);
  CHECK(resolved.hardWarn == 2);
  CHECK(resolved.warn == targetTolerance("lit").thresholds.warn);
}

TEST_CASE("diff: the command's usage errors are exit 5, --help is 0 and lists the exit codes" *
          doctest::test_suite("diff")) {
  Cli cli = runCli({});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "expected two images"));
  cli = runCli({"a.exr", "b.exr", "--fail"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "--fail needs a value"));
  cli = runCli({"a.exr", "b.exr", "--failpercent", "150"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "--failpercent"));
  CHECK(runCli({"a.exr", "b.exr", "--warn", "-1"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--warn", "nan"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--bogus"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--json=yes"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--channels", "R,,G"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--out", "diff.tif"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "c.exr"}).exitCode == 5);
  cli = runCli({"a.exr", "b.exr", "--target", "normals"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "expected one of position, normal,"));
  cli = runCli({"--help"});
  CHECK(cli.exitCode == 0);
  CHECK(contains(cli.out, "usage: headlight diff"));
  CHECK(contains(cli.out, "3 structural mismatch"));
  CHECK(contains(cli.out, "5 usage error"));
  CHECK(contains(cli.out, "angle-degrees"));
  CHECK(contains(cli.out, "preview"));
  cli = runCli({"a.exr", "b.exr", "--metric", "psnr"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "flip"));  // the choices are listed
  // Missing files are a file error, not a usage error.
  CHECK(runCli({"/nonexistent/a.exr", "/nonexistent/b.exr"}).exitCode == 4);
}

TEST_CASE("diff: lit is judged by HDR-FLIP, preview.png by LDR-FLIP, and --metric picks another measure" *
          doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_flip");
  fs::create_directories(folder / "b");
  // HDR radiance up to ~3, fully covered.
  TestImage lit = gradient(32, 32, {"R", "G", "B", "A"});
  for (std::size_t i = 0; i < lit.pixels.size(); ++i) lit.pixels[i] = i % 4 == 3 ? 1.0f : 3.0f * lit.pixels[i];
  write(folder / "lit.exr", lit);
  write(folder / "b" / "lit.exr", lit);
  DiffResult result = diffImages(folder / "lit.exr", folder / "b" / "lit.exr");
  CHECK(result.metric == DiffMetric::Flip);
  CHECK(result.status == DiffStatus::Pass);
  REQUIRE(result.channels.size() == 2);  // flip of R, G, B; coverage A on its own
  CHECK(result.channels[0].name == "flip");
  CHECK(result.channels[0].sources == std::vector<std::string>{"R", "G", "B"});
  CHECK(result.channels[1].name == "A");
  CHECK(result.maxError == 0);
  REQUIRE(result.flip);
  CHECK(result.flip->hdr);
  CHECK(result.flip->exposureCount >= 2);

  // A 6x6 block twice as bright: 3.5 % of the pixels, clearly visible: FAIL,
  // with the library's HDR-FLIP mean (A is the reference).
  TestImage brighter = lit;
  for (int y = 10; y < 16; ++y)
    for (int x = 10; x < 16; ++x)
      for (int c = 0; c < 3; ++c) brighter.at(x, y, c) *= 2.0f;
  write(folder / "b" / "lit.exr", brighter);
  result = diffImages(folder / "lit.exr", folder / "b" / "lit.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.maxChannel == "flip");
  const flip::FlipResult direct = flip::hdrFlip({lit.pixels.data(), 32, 32, 4}, {brighter.pixels.data(), 32, 32, 4});
  CHECK(result.channels[0].meanError == doctest::Approx(direct.mean).epsilon(1e-5));
  CHECK(result.channels[0].maxError == doctest::Approx(direct.maximum).epsilon(1e-5));
  CHECK(result.maxX >= 8);
  CHECK(result.maxX <= 17);
  CHECK(result.channels[1].maxError == 0);

  // --out: the FLIP map itself in diff.exr's error channel, magma in the PNG
  // (0 is magma's black bottom, whatever the fail threshold).
  const fs::path exr = folder / "flip_diff.exr";
  const Cli written =
      runCli({(folder / "lit.exr").string(), (folder / "b" / "lit.exr").string(), "--out", exr.string(), "--json"});
  CHECK(written.exitCode == 2);
  const nlohmann::json j = nlohmann::json::parse(written.out);
  CHECK(j["metric"] == "flip");
  CHECK(j["flip"]["variant"] == "hdr");
  CHECK(j["flip"]["pixels_per_degree"].get<double>() == doctest::Approx(67.02).epsilon(1e-3));
  CHECK(j["flip"]["exposures"].get<int>() == direct.exposureCount);
  OIIO::ImageBuf diff(exr.string());
  REQUIRE(diff.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  const int error = diff.spec().channelindex("error");
  CHECK(diff.getchannel(result.maxX, result.maxY, 0, error) == doctest::Approx(direct.maximum).epsilon(1e-5));
  OIIO::ImageBuf png((folder / "flip_diff.png").string());
  REQUIRE(png.read());
  CHECK(png.getchannel(31, 31, 0, 0) < 0.02f);  // FLIP 0 there: magma's near-black
  CHECK(png.getchannel(31, 31, 0, 2) < 0.05f);
  // Beside the map: A and B as FLIP saw them (tone mapped, 8-bit), and the
  // HTML report showing the three with the numbers.
  for (const char* name : {"flip_diff_a.png", "flip_diff_b.png"}) {
    OIIO::ImageBuf view((folder / name).string());
    REQUIRE(view.read());
    CHECK(view.spec().width == 32);
    CHECK(view.nchannels() == 3);
  }
  OIIO::ImageBuf viewA((folder / "flip_diff_a.png").string()), viewB((folder / "flip_diff_b.png").string());
  REQUIRE(viewA.read());
  REQUIRE(viewB.read());
  CHECK(viewB.getchannel(12, 12, 0, 0) > viewA.getchannel(12, 12, 0, 0));  // the brighter block
  CHECK(viewB.getchannel(30, 30, 0, 0) == viewA.getchannel(30, 30, 0, 0));
  std::ifstream html(folder / "flip_diff.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  for (const char* part : {"flip_diff_a.png", "flip_diff_b.png", "flip_diff.png", "HDR-FLIP", "FAIL"})
    CHECK_MESSAGE(contains(page, part), part);

  // Coverage is compared absolutely beside the FLIP.
  TestImage uncovered = lit;
  for (int x = 0; x < 32; ++x) uncovered.at(x, 0, 3) = 0;  // 3 % of the pixels
  write(folder / "b" / "lit.exr", uncovered);
  result = diffImages(folder / "lit.exr", folder / "b" / "lit.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.maxChannel == "A");

  // Without R, G, B (--channels) FLIP cannot apply: absolute per channel.
  DiffOptions someChannels;
  someChannels.channels = {"R", "A"};
  CHECK(diffImages(folder / "lit.exr", folder / "b" / "lit.exr", someChannels).metric == DiffMetric::Absolute);

  // --metric flip on a file that is no target: lit's thresholds; and the
  // other way, lit judged by relative-to-value gets emissive's.
  write(folder / "golden.exr", lit);
  write(folder / "b" / "golden.exr", brighter);
  DiffOptions asFlip;
  asFlip.metric = DiffMetric::Flip;
  result = diffImages(folder / "golden.exr", folder / "b" / "golden.exr", asFlip);
  CHECK(result.metric == DiffMetric::Flip);
  CHECK(result.thresholds.fail == targetTolerance("lit").thresholds.fail);
  CHECK(result.thresholds.failMean == targetTolerance("lit").thresholds.failMean);
  DiffOptions asRelative;
  asRelative.metric = DiffMetric::RelativeToValue;
  CHECK(resolveThresholds("lit", asRelative).fail == targetTolerance("emissive").thresholds.fail);

  // preview.png: 8-bit sRGB, LDR-FLIP of the decoded values.
  auto writePng = [](const fs::path& path, const TestImage& image) {
    OIIO::ImageSpec spec(image.width, image.height, int(image.channels.size()), OIIO::TypeDesc::UINT8);
    auto output = OIIO::ImageOutput::create(path.string());
    REQUIRE(output);
    REQUIRE(output->open(path.string(), spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
    REQUIRE(output->close());
  };
  TestImage preview = gradient(32, 32, {"R", "G", "B"});
  TestImage tinted = preview;
  for (int y = 0; y < 32; ++y)
    for (int x = 20; x < 32; ++x) tinted.at(x, y, 2) = 0.1f;  // 37 % of the picture loses its blue
  writePng(folder / "preview.png", preview);
  writePng(folder / "b" / "preview.png", tinted);
  result = diffImages(folder / "preview.png", folder / "b" / "preview.png");
  CHECK(result.metric == DiffMetric::Flip);
  REQUIRE(result.flip);
  CHECK_FALSE(result.flip->hdr);
  CHECK(result.status == DiffStatus::Fail);
  // The same as LDR-FLIP of the decoded 8-bit values.
  std::vector<float> decodedA, decodedB;
  for (std::size_t i = 0; i < preview.pixels.size(); ++i) {
    decodedA.push_back(srgbToLinear(std::round(preview.pixels[i] * 255.0f) / 255.0f));
    decodedB.push_back(srgbToLinear(std::round(tinted.pixels[i] * 255.0f) / 255.0f));
  }
  const double ldrMean = flip::ldrFlip({decodedA.data(), 32, 32, 3}, {decodedB.data(), 32, 32, 3}).mean;
  CHECK(result.channels[0].meanError == doctest::Approx(ldrMean).epsilon(1e-4));
  writePng(folder / "b" / "preview.png", preview);
  CHECK(diffImages(folder / "preview.png", folder / "b" / "preview.png").status == DiffStatus::Pass);
  fs::remove_all(folder);
}

TEST_CASE("diff: --out replaces only what an earlier diff wrote, never a compared folder (issue 32)" *
          doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_owned");
  const fs::path a = folder / "a", b = folder / "b";
  fs::create_directories(a);
  fs::create_directories(b);
  const TestImage lit = gradient(8, 8, {"A", "B", "G", "R"});
  TestImage changed = lit;
  changed.at(2, 2, 1) += 0.5f;
  write(a / "lit.exr", lit);
  write(b / "lit.exr", changed);
  auto readText = [](const fs::path& path) {
    std::ifstream file(path);
    return std::string(std::istreambuf_iterator<char>(file), {});
  };

  // Folder mode: the compared folder itself is refused, even with --force.
  for (const char* force : {"", "--force"}) {
    std::vector<std::string> args{a.string(), b.string(), "--out", b.string()};
    if (*force) args.push_back(force);
    const Cli intoB = runCli(args);
    CHECK(intoB.exitCode == 5);
    CHECK(contains(intoB.err, "is the compared folder"));
  }
  CHECK_FALSE(fs::exists(b / "report.html"));

  // A user's report.html in --out: refused, untouched; --force replaces it;
  // the next diff there replaces its own files without asking.
  const fs::path out = folder / "diffs";
  fs::create_directories(out);
  { std::ofstream(out / "report.html") << "<html>my notes</html>"; }
  const Cli refused = runCli({a.string(), b.string(), "--out", out.string()});
  CHECK(refused.exitCode == 5);
  CHECK(contains(refused.err, (out / "report.html").string() + " exists and no earlier headlight diff report"));
  CHECK(readText(out / "report.html") == "<html>my notes</html>");
  CHECK(runCli({a.string(), b.string(), "--out", out.string(), "--force"}).exitCode != 5);
  CHECK(contains(readText(out / "report.html"), "<title>headlight diff</title>"));
  CHECK(fs::exists(out / "lit_diff.png"));
  CHECK(runCli({a.string(), b.string(), "--out", out.string()}).exitCode != 5);

  // File mode: a PNG of the user's beside --out's EXR likewise.
  const fs::path exr = folder / "single" / "d.exr";
  fs::create_directories(exr.parent_path());
  { std::ofstream(folder / "single" / "d.png") << "not ours"; }
  const std::vector<std::string> fileArgs{(a / "lit.exr").string(), (b / "lit.exr").string(), "--out", exr.string()};
  const Cli besidePng = runCli(fileArgs);
  CHECK(besidePng.exitCode == 5);
  CHECK(contains(besidePng.err, "d.png exists"));
  CHECK(readText(folder / "single" / "d.png") == "not ours");
  CHECK_FALSE(fs::exists(exr));
  std::vector<std::string> forced = fileArgs;
  forced.push_back("--force");
  CHECK(runCli(forced).exitCode != 5);
  CHECK(fs::exists(exr));
  CHECK(runCli(fileArgs).exitCode != 5);  // d.html is now a diff's report
  fs::remove_all(folder);
}

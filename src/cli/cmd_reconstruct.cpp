// imagepro-cli reconstruct: the whole pipeline over images or the virtual source,
// one pose row per frame (per target of a set) in the CSV format of docs/conventions.md (or JSON).
#include <cstdio>

#include "cli/command.h"
#include "cli/enum_options.h"
#include "cli/frame_input.h"
#include "cli/option_ranges.h"
#include "cli/virtual_motion_options.h"
#include "core/pipeline/data_out.h"
#include "core/pipeline/engine.h"
#include "core/pipeline/frame_record.h"
#include "core/pipeline/frame_clock.h"
#include "core/pipeline/pose_stream.h"

namespace imagepro::cli {
namespace {

// One frame as a JSON object on one line: the record's fields that have a value, and when
// the spots could not tell the rim's two circles apart (AmbiguousPose, or ok with the pose
// halfway between them) both as "candidates", the one that fits the spots better first.
std::string jsonRow(const FrameResult& r) {
  std::string row = "{" + recordJsonMembers(r, kReconstructJson);
  if (r.ambiguous_poses) {
    row += ",\"candidates\":[";
    for (std::size_t k = 0; k < r.ambiguous_poses->size(); ++k)
      row += (k ? ",{" : "{") + poseJsonMembers(&(*r.ambiguous_poses)[k]) + "}";
    row += ']';
  }
  return row + "}";
}

// Every row of the frame (one per target of a set), as JSON objects separated by commas.
std::string jsonRows(const FrameResult& r) {
  if (!r.set_of_targets) return jsonRow(r);
  std::string rows;
  FrameResult row;
  for (std::size_t k = 0; k < recordRowCount(r); ++k) {
    recordRow(r, k, row);
    rows += (k ? ",\n  " : "") + jsonRow(row);
  }
  return rows;
}

// The stream section of the settings, switched on by --stream udp://HOST:PORT; --stream-format
// changes the format of either.
StreamOptions streamOptions(const Args& args, StreamOptions options) {
  if (const auto url = args.value("stream")) {
    std::string error;
    if (!parseStreamUrl(*url, options, error)) throw UsageError("--stream: " + error);
    options.enabled = true;
  }
  options.format = enumOption<StreamFormat>(args, "stream-format", options.format);
  return options;
}

int run(const Args& args) {
  std::vector<std::string> known = kFrameInputOptions;
  known.insert(known.end(), {"format", "data-out", "truth", "no-pace", "stream", "stream-format"});
  known.insert(known.end(), kVirtualMotionOptions.begin(), kVirtualMotionOptions.end());
  args.rejectUnknown(known);
  const std::string format = args.valueOr("format", "csv");
  if (format != "csv" && format != "json") throw UsageError("--format must be csv or json");
  Settings settings = loadConfigForInput(args);
  for (const std::string& key : kVirtualMotionOptions)
    if (args.has(key) && !args.has("virtual")) throw UsageError("--" + key + " goes with --virtual");
  applyVirtualMotionOptions(args, settings.virtual_scene);
  checkOptionRanges(settings, kVirtualMotionOptionKeys);
  auto source = openFrameInput(args, settings);
  const bool with_truth = args.has("truth");

  DataOut data_out;
  if (const auto path = args.value("data-out")) {
    std::string error;
    if (!ok(data_out.open(*path, ExistingFile::Fail, error))) throw InputError(error);
  }

  // An address that does not resolve is reported and the run goes on: the frames still
  // reach the standard output and the data-out file.
  PoseStream stream;
  if (const StreamOptions options = streamOptions(args, settings.stream); options.enabled) {
    std::string error;
    if (!ok(stream.open(options, error))) std::fprintf(stderr, "stream: %s\n", error.c_str());
  }

  Engine engine(settings);
  FrameResult result;
  const std::uint16_t csv_fields = kReconstructCsv | (with_truth ? kTruthCsv : 0);
  if (format == "csv")
    std::printf("%s\n", recordCsvHeader(csv_fields).c_str());
  else
    std::printf("[");
  bool first = true;
  // Camera and Virtual sources run at their own frame rate unless told otherwise.
  FramePacer pacer(args.has("no-pace") ? 0.0 : source->frameRateHz());
  LoopMeter meter;
  std::int64_t frames = 0, reconstructed = 0;
  for (;;) {
    pacer.wait();
    if (engine.step(*source, result) == Status::EndOfStream) break;
    meter.tick();
    ++frames;
    if (result.pose) ++reconstructed;
    const std::string frame = frameLabel(result);
    if (format == "csv")
      std::printf("%s\n", recordCsvRows(result, csv_fields).c_str());
    else
      std::printf("%s\n  %s", first ? "" : ",", jsonRows(result).c_str());
    first = false;
    if (!ok(result.status) && !source->lastError().empty())
      std::fprintf(stderr, "%s\n", frameProblem(frame, source->lastError()).c_str());
    if (data_out.isOpen()) {
      std::string error;
      if (!data_out.write(result, error)) std::fprintf(stderr, "data out stopped: %s\n", error.c_str());
    }
    stream.send(result);
    std::fflush(stdout);
  }
  if (format == "json") std::printf("\n]\n");
  std::fprintf(stderr, "%lld frames, %lld reconstructed", static_cast<long long>(frames),
               static_cast<long long>(reconstructed));
  if (meter.hz() > 0) std::fprintf(stderr, "; %.1f Hz at %.0f %% of one core", meter.hz(), meter.cpuPercent());
  std::fprintf(stderr, "\n");
  if (stream.isActive()) {
    std::fprintf(stderr, "stream %s\n", stream.report().c_str());
    if (!stream.problem().empty()) std::fprintf(stderr, "stream: %s\n", stream.problem().c_str());
  }
  return 0;
}

// `text` in lines of at most `width` characters, each after `indent`.
std::string wrapped(std::string_view text, std::size_t width, std::string_view indent) {
  std::string out, line;
  while (!text.empty()) {
    const std::size_t space = text.find(' ');
    const std::string_view word = text.substr(0, space);
    text = space == std::string_view::npos ? std::string_view{} : text.substr(space + 1);
    if (!line.empty() && indent.size() + line.size() + 1 + word.size() > width) {
      out += std::string(indent) + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + std::string(word);
  }
  if (!line.empty()) out += std::string(indent) + line + "\n";
  return out;
}

// The CSV's columns as the frame record has them, and what its fields beyond the pose say.
std::string columnsHelp() {
  std::string text = "\nOne row per frame: " + recordCsvHeader(kReconstructCsv) + ".\n";
  for (const FrameField& f : frameFields()) {
    // The pose and its truth are described above; every other field here.
    if (!(f.outputs & (kReconstructCsv | kReconstructJson)) || f.unit == "deg" || f.unit == "mm" ||
        f.name == "frame" || f.name == "status")
      continue;
    text += wrapped(std::string(f.name) + ((f.outputs & kReconstructCsv) ? "" : " (JSON only)") + ": " +
                        std::string(f.description),
                    86, "  ");
  }
  return text;
}

const CommandRegistration kRegistration{{
    "reconstruct",
    "detect the target and reconstruct its pose in every frame (CSV or JSON)",
    std::string("usage: imagepro-cli reconstruct [--config FILE] [--format csv|json] [--truth]\n"
                "                                [--data-out FILE] [--stream udp://HOST:PORT\n"
                "                                [--stream-format json|opentrack]] INPUT\n\n") +
        kFrameInputHelp + "\n  with --virtual, the settings' motion may be changed:\n" + virtualMotionHelp() + columnsHelp() +
        "A frame without a target is a row with the error's name, not a failed command.\n"
        "A pose that cannot be trusted is not ok either: AmbiguousPose (the rim's two\n"
        "possible poses fit the spots about equally; with --format json both are given as\n"
        "\"candidates\", the better-fitting first) or PoseInconsistent (the pose puts the\n"
        "spots or the rim away from where the image has them). When the two lie within\n"
        "twice ambiguity_tolerance_deg (" +
        numberText(ReconstructionOptions{}.ambiguity_tolerance_deg) +
        " degrees by default) of each other, the frame is ok with the pose\n"
        "halfway between them, and the JSON gives both as \"candidates\" too.\n"
        "  --truth          add the ground-truth pose columns (virtual frames)\n"
        "  --no-pace        run a camera or virtual source as fast as possible, not at its frame rate\n"
        "  --data-out FILE  also write the full data-out CSV (regions, stage times) to FILE\n"
        "  --stream udp://HOST:PORT\n"
        "                   also send every frame as it is made, one UDP datagram each\n"
        "                   (docs/streaming.md); the settings' stream section when not given.\n"
        "                   A full socket buffer drops datagrams; the counts and any problem\n"
        "                   (StreamHostNotFound, StreamUnreachable, StreamRefused) close the summary\n"
        "  --stream-format FORMAT\n" +
        choicesHelp<StreamFormat>(),
    {"virtual", "truth", "no-pace"},
    run,
}};

}  // namespace
}  // namespace imagepro::cli

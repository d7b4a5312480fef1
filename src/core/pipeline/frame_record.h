#pragma once
// The frame record: every field a frame's outputs carry, described once (name, unit,
// format, which outputs carry it). The data-out CSV, reconstruct's CSV and JSON, the UDP
// stream's JSON, the Python result's scalar fields and the GUI's results text all take
// their names, formats and fields from this table; adding a field is one entry in
// frame_record.cpp and its computation. docs/conventions.md says which columns are stable.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "core/pipeline/frame_result.h"

namespace imagepro {

// The outputs that write a frame.
enum FrameOutput : std::uint16_t {
  kDataOutCsv = 1 << 0,       // Data Out (GUI, reconstruct --data-out)
  kReconstructCsv = 1 << 1,   // imagepro-cli reconstruct
  kTruthCsv = 1 << 2,         // ... --truth adds these
  kReconstructJson = 1 << 3,  // ... --format json (a field without a value is left out)
  kStreamJson = 1 << 4,       // the UDP stream's JSON datagram (a field without a value is null)
  kPython = 1 << 5,           // a property of imagepro.Result
  kResultsText = 1 << 6,      // a line of the GUI's results text
};

// One field's value in one frame: a number, a text, or none (an empty CSV cell, JSON null).
struct FieldValue {
  enum class Kind : std::uint8_t { None, Number, Text } kind = Kind::None;
  double number = 0.0;
  std::string text;
};

struct FrameField {
  std::string_view name;         // the CSV column, JSON key and Python attribute
  std::string_view unit;         // "deg", "mm", "s", "px", "us", or "" for shares and names
  std::string_view label;        // the results text's label; empty: not shown there
  std::string_view description;  // one line for the Python docstring and the docs
  int decimals = 0;              // how numbers are printed (CSV, JSON, results text)
  std::uint16_t outputs = 0;     // FrameOutput bits
  FieldValue (*value)(const FrameResult&, int) = nullptr;
  int arg = 0;  // passed to value: which of a family (pose component, stage, region side)
};

// Every field, in the order the outputs write them.
std::span<const FrameField> frameFields();

// The CSV header (without a newline) and one row of `output`'s fields (kTruthCsv rides on
// kReconstructCsv: pass both).
std::string recordCsvHeader(std::uint16_t output);
std::string recordCsvRow(const FrameResult& result, std::uint16_t output);
// A frame's output rows: with a set of targets (set_of_targets), one per target told
// (told_targets.h), else (and when none was told) one, the frame itself. Row `k` is the
// frame's fields with the target's own: status, pose, id, searched and detected boxes,
// self-check and poses in the chosen frames.
std::size_t recordRowCount(const FrameResult& frame);
void recordRow(const FrameResult& frame, std::size_t k, FrameResult& row);
// Every row of the frame as CSV, one per line (no newline after the last).
std::string recordCsvRows(const FrameResult& frame, std::uint16_t output);
// The JSON members of `output`'s fields, "key":value separated by commas, without braces:
// a field without a value is null in the stream and left out of reconstruct's JSON.
std::string recordJsonMembers(const FrameResult& result, FrameOutput output);
// A pose as JSON members in the pose columns' names, six decimals; null without one.
std::string poseJsonMembers(const Pose* pose);
// A number or text as CSV and JSON print it (FieldValue::None: "" and "null").
std::string fieldCsv(const FrameField& field, const FieldValue& value);
std::string fieldJson(const FrameField& field, const FieldValue& value);

}  // namespace imagepro

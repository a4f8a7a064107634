// quakeview-prep mdof: one shear building under one ground motion, by the reference solver of
// engine::seismic (Newmark average acceleration, Newton iterations for Bouc–Wen storeys).
//
// Options are a contract (extend, never rename): --storeys N --mass KG --stiffness N_PER_M
// [--height M] [--damping RATIO] [--modal-damping] [--linear | --bouc-wen ALPHA,N,GAMMA,BETA]
// [--rayleigh A0,A1] [--free-vibration S] --motion FILE [--dt S] [--units g|m/s2|cm/s2] [--scale S]
// [--substeps N] [--json]. Damping without --modal-damping or --rayleigh: Rayleigh with --damping on
// modes 1 and 2 (one storey: --damping at mode 1).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "Commands.h"
#include "qv/core/JsonWriter.h"
#include "qv/core/NumberFormat.h"
#include "qv/prep/Cli.h"
#include "qv/seismic/GroundMotionReader.h"
#include "qv/seismic/ReferenceSolver.h"
#include "qv/seismic/ShearBuilding.h"

namespace qv::prep {
namespace {

constexpr const char* kUsage =
    "usage: quakeview-prep mdof --storeys N --mass KG --stiffness N_PER_M --motion FILE [options]\n"
    "\n"
    "One lumped-mass shear building (floor 1 and storey 1 first) under a ground motion, integrated by\n"
    "Newmark's average acceleration method.\n"
    "\n"
    "  --storeys N              number of storeys (1..1000)\n"
    "  --mass KG                floor mass: one value for every floor or N comma-separated values\n"
    "  --stiffness N_PER_M      storey stiffness: one value or N values\n"
    "  --height M               storey height: one value or N values (enables drift ratios, base moment)\n"
    "  --damping RATIO          damping ratio (default 0.05): modal with --modal-damping, otherwise\n"
    "                           Rayleigh on modes 1 and 2\n"
    "  --modal-damping          classical modal damping, --damping in every mode\n"
    "  --rayleigh A0,A1         Rayleigh damping C = A0 M + A1 K (initial stiffness)\n"
    "  --linear                 linear storeys (the default)\n"
    "  --bouc-wen A,N,G,B       Bouc-Wen storeys as OpenSees' BoucWen material (alpha, n, gamma, beta;\n"
    "                           Ao = 1, no degradation; z in metres)\n"
    "  --motion FILE            PEER AT2, one value a line, or two columns (time, acceleration)\n"
    "  --dt S                   time step for files without one\n"
    "  --units g|m/s2|cm/s2     units for files that do not state them\n"
    "  --scale S                multiplies the record (default 1)\n"
    "  --free-vibration S       seconds simulated after the record (default 0)\n"
    "  --substeps N             N equal sub-steps per record step with OpenSees' backward-Euler Bouc-Wen\n"
    "                           update (default: automatic, dt <= T1/20 and T2/10, the update integrated\n"
    "                           exactly along each step for n = 1 and 2)\n"
    "  --json                   print one JSON object instead of the table\n";

int usageError(const std::string& message) {
  std::fprintf(stderr, "quakeview-prep mdof: %s\n(run 'quakeview-prep mdof --help' for the options)\n",
               message.c_str());
  return kExitUsage;
}

// "V" or "V1,...,Vn": one value for every storey or exactly `count`, each finite and > 0.
bool parsePerStorey(const std::string& flag, const std::string& text, std::size_t count, std::vector<double>& out,
                    std::string& error) {
  const std::size_t values = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
  if (values != 1 && values != count) {
    error = "--" + flag + " takes 1 or " + std::to_string(count) + " values, not " + std::to_string(values);
    return false;
  }
  const auto parsed = parseNumberList(text, values);
  if (!parsed) {
    error = "--" + flag + " must be comma-separated numbers, not '" + text + "'";
    return false;
  }
  for (const double v : *parsed) {
    if (!(v > 0.0)) {
      error = "--" + flag + " values must be > 0";
      return false;
    }
  }
  out = values == 1 ? std::vector<double>(count, parsed->front()) : *parsed;
  return true;
}

}  // namespace

int runMdof(const CommandArgs& args) {
  const std::vector<Args::Spec> specs = {
      {"storeys"},       {"mass"},     {"stiffness"}, {"height"},         {"damping"},     {"modal-damping", false},
      {"linear", false}, {"bouc-wen"}, {"rayleigh"},  {"free-vibration"}, {"motion"},      {"dt"},
      {"units"},         {"scale"},    {"substeps"},  {"json", false},    {"help", false},
  };
  std::string error;
  const auto parsed = Args::parse(args, specs, error);
  if (!parsed) return usageError(error);
  const Args& a = *parsed;
  if (a.has("help")) {
    std::fputs(kUsage, stdout);
    return kExitOk;
  }
  if (!a.positional().empty()) return usageError("unexpected argument '" + a.positional().front() + "'");
  for (const char* required : {"storeys", "mass", "stiffness", "motion"}) {
    if (!a.has(required)) return usageError(std::string("--") + required + " is required");
  }

  const auto storeysValue = parseInteger(*a.value("storeys"));
  if (!storeysValue || *storeysValue < 1 || *storeysValue > 1000) {
    return usageError("--storeys must be a whole number from 1 to 1000, not '" + *a.value("storeys") + "'");
  }
  const auto n = static_cast<std::size_t>(*storeysValue);
  seismic::ShearBuilding building;
  if (!parsePerStorey("mass", *a.value("mass"), n, building.floorMassKg, error)) return usageError(error);
  if (!parsePerStorey("stiffness", *a.value("stiffness"), n, building.storeyStiffnessNPerM, error))
    return usageError(error);
  if (a.has("height") && !parsePerStorey("height", *a.value("height"), n, building.storeyHeightM, error))
    return usageError(error);

  // Storey law.
  if (a.has("linear") && a.has("bouc-wen")) return usageError("--linear and --bouc-wen exclude each other");
  std::string lawText = "linear";
  if (a.has("bouc-wen")) {
    const auto p = parseNumberList(*a.value("bouc-wen"), 4);
    if (!p) return usageError("--bouc-wen takes ALPHA,N,GAMMA,BETA (four numbers), not '" + *a.value("bouc-wen") + "'");
    const auto law = seismic::BoucWenStorey::fromOpenSees((*p)[0], (*p)[1], (*p)[2], (*p)[3]);
    if (!law) return usageError("--bouc-wen: " + law.error());
    building.hysteresis.assign(n, *law);
    lawText = "Bouc-Wen alpha " + formatDouble((*p)[0]) + ", n " + formatDouble((*p)[1]) + ", gamma " +
              formatDouble((*p)[2]) + ", beta " + formatDouble((*p)[3]) + " (yield displacement " +
              formatDouble(law->yieldDisplacementM) + " m)";
  }

  // Damping.
  if (a.has("modal-damping") && a.has("rayleigh"))
    return usageError("--modal-damping and --rayleigh exclude each other");
  if (a.has("rayleigh") && a.has("damping"))
    return usageError("--damping applies to modal or default Rayleigh damping; --rayleigh sets the coefficients");
  double ratio = 0.05;
  if (a.has("damping")) {
    const auto v = parseDouble(*a.value("damping"));
    if (!v || *v < 0.0 || *v >= 1.0)
      return usageError("--damping must be a ratio in [0, 1), not '" + *a.value("damping") + "'");
    ratio = *v;
  }
  if (a.has("rayleigh")) {
    const auto p = parseNumberList(*a.value("rayleigh"), 2);
    if (!p || (*p)[0] < 0.0 || (*p)[1] < 0.0) return usageError("--rayleigh takes A0,A1 (two numbers >= 0)");
    building.damping = seismic::Damping::rayleigh((*p)[0], (*p)[1]);
  } else if (a.has("modal-damping")) {
    building.damping = seismic::Damping::modal(ratio);
  }
  if (const Status s = seismic::validateShearBuilding(building); !s) return usageError(s.error());
  const auto modes = seismic::computeModes(building);
  if (!modes) return usageError(modes.error());
  std::string dampingText;
  if (a.has("rayleigh")) {
    dampingText = "Rayleigh a0 " + formatDouble(building.damping.massCoefficient) + " 1/s, a1 " +
                  formatDouble(building.damping.stiffnessCoefficient) + " s";
  } else if (a.has("modal-damping")) {
    dampingText = "classical modal, " + formatDouble(100.0 * ratio) + " % in every mode";
  } else {
    const double w2 = n > 1 ? modes->circularFrequencies[1] : 0.0;
    building.damping = seismic::Damping::rayleighFromModes(ratio, modes->circularFrequencies[0], w2);
    dampingText = "Rayleigh, " + formatDouble(100.0 * ratio) + (n > 1 ? " % on modes 1 and 2" : " % on mode 1") +
                  " (a0 " + formatDouble(building.damping.massCoefficient) + " 1/s, a1 " +
                  formatDouble(building.damping.stiffnessCoefficient) + " s)";
  }

  // Motion and run options.
  seismic::GroundMotionReadOptions read;
  if (a.has("dt")) {
    const auto v = parseDouble(*a.value("dt"));
    if (!v || *v <= 0.0 || *v > 10.0)
      return usageError("--dt must be a step in (0, 10] s, not '" + *a.value("dt") + "'");
    read.timeStepS = *v;
  }
  if (a.has("units")) {
    read.units = seismic::parseAccelerationUnit(*a.value("units"));
    if (!read.units) return usageError("--units must be g, m/s2 or cm/s2, not '" + *a.value("units") + "'");
  }
  seismic::ReferenceOptions options;
  if (a.has("scale")) {
    const auto v = parseDouble(*a.value("scale"));
    if (!v) return usageError("--scale must be a number, not '" + *a.value("scale") + "'");
    options.scale = *v;
  }
  if (a.has("free-vibration")) {
    const auto v = parseDouble(*a.value("free-vibration"));
    if (!v || *v < 0.0 || *v > 1e5)
      return usageError("--free-vibration must be seconds in [0, 1e5], not '" + *a.value("free-vibration") + "'");
    options.freeVibrationSeconds = *v;
  }
  if (a.has("substeps")) {
    const auto v = parseInteger(*a.value("substeps"));
    if (!v || *v < 1 || *v > 1000) return usageError("--substeps must be a whole number from 1 to 1000");
    options.substeps = static_cast<int>(*v);
  }
  options.keepHistory = false;

  seismic::GroundMotionSource source;
  const std::string motionPath = *a.value("motion");
  const auto motion = seismic::readGroundMotionFile(motionPath, read, &source);
  if (!motion) {
    std::fprintf(stderr, "quakeview-prep mdof: %s\n", motion.error().c_str());
    return kExitDataError;
  }
  const auto response = seismic::solveReference(building, *motion, options);
  if (!response) {
    std::fprintf(stderr, "quakeview-prep mdof: %s\n", response.error().c_str());
    return kExitDataError;
  }
  const seismic::ReferenceResponse& r = *response;
  const bool heights = !building.storeyHeightM.empty();
  const double peakG =
      motion->accelerationMps2.empty() ? 0.0 : motion->accelerationMps2[motion->peakIndex()] / seismic::kGravityMps2;
  const double peakTime = static_cast<double>(motion->peakIndex() + 1) * motion->timeStepS;

  if (a.has("json")) {
    JsonWriter w;
    w.beginObject();
    w.field("storeys", static_cast<std::uint64_t>(n));
    w.key("periods_s").beginArray();
    for (const double t : r.periodsS) w.value(t);
    w.endArray();
    w.field("peak_roof_displacement_m", r.peakRoofDisplacementM);
    w.field("peak_base_shear_n", r.peakBaseShearN);
    if (heights) w.field("peak_base_moment_nm", r.peakBaseMomentNm);
    w.field("peak_floor_acceleration_mps2", r.peakFloorAccelerationMps2);
    w.key("peak_drift_m").beginArray();
    for (const double d : r.peakDriftM) w.value(d);
    w.endArray();
    if (heights) {
      w.key("peak_drift_ratio").beginArray();
      for (const double d : r.peakDriftRatio) w.value(d);
      w.endArray();
    }
    w.key("peak_storey_shear_n").beginArray();
    for (const double v : r.peakStoreyShearN) w.value(v);
    w.endArray();
    w.field("residual_roof_displacement_m", r.residualRoofDisplacementM);
    w.key("residual_drift_m").beginArray();
    for (const double d : r.residualDriftM) w.value(d);
    w.endArray();
    w.key("model").beginObject();
    w.field("storey_law", a.has("bouc-wen") ? "bouc-wen" : "linear");
    w.field("damping", a.has("rayleigh") ? "rayleigh" : (a.has("modal-damping") ? "modal" : "rayleigh-modes-1-2"));
    w.field("rayleigh_a0", building.damping.massCoefficient);
    w.field("rayleigh_a1", building.damping.stiffnessCoefficient);
    if (building.damping.kind == seismic::DampingKind::Modal) w.field("modal_ratio", ratio);
    w.endObject();
    w.key("motion").beginObject();
    w.field("name", motion->name);
    w.field("format", seismic::groundMotionFormatName(source.format));
    w.field("points", static_cast<std::uint64_t>(motion->size()));
    w.field("dt_s", motion->timeStepS);
    w.field("units", seismic::accelerationUnitName(source.units));
    w.field("scale", options.scale);
    w.field("peak_g", peakG);
    w.field("peak_time_s", peakTime);
    w.endObject();
    w.key("solver").beginObject();
    w.field("method", "newmark-average-acceleration");
    w.field("substeps", r.stats.substeps);
    w.field("steps", static_cast<std::uint64_t>(r.stats.steps));
    w.field("newton_solves", static_cast<std::uint64_t>(r.stats.newtonIterations));
    w.field("split_steps", static_cast<std::uint64_t>(r.stats.splitSteps));
    w.field("free_vibration_s", options.freeVibrationSeconds);
    w.endObject();
    w.endObject();
    std::printf("%s\n", w.str().c_str());
    return kExitOk;
  }

  std::printf("%zu-storey shear building, %s\n", n, lawText.c_str());
  std::printf("damping: %s\n", dampingText.c_str());
  std::printf("motion: %s (%s, %zu points at %s s, units %s%s), scale %s, peak %s g at %s s\n", motion->name.c_str(),
              std::string(seismic::groundMotionFormatName(source.format)).c_str(), motion->size(),
              formatDouble(motion->timeStepS).c_str(), std::string(seismic::accelerationUnitName(source.units)).c_str(),
              source.unitsFromFile ? " from the file" : "", formatDouble(options.scale).c_str(),
              formatDouble(peakG, 4).c_str(), formatDouble(peakTime, 4).c_str());
  std::printf("solver: Newmark average acceleration, %d sub-step(s) per record step, %zu steps, %zu Newton solves\n\n",
              r.stats.substeps, r.stats.steps, r.stats.newtonIterations);
  std::printf("mode  period (s)  frequency (Hz)\n");
  for (std::size_t j = 0; j < r.periodsS.size(); ++j) {
    std::printf("%4zu  %10.4f  %14.4f\n", j + 1, r.periodsS[j], 1.0 / r.periodsS[j]);
  }
  std::printf("\npeak roof displacement      %.6g m\n", r.peakRoofDisplacementM);
  std::printf("peak base shear             %.7g N\n", r.peakBaseShearN);
  if (heights) std::printf("peak base moment            %.7g N m\n", r.peakBaseMomentNm);
  std::printf("peak floor acceleration     %.4g m/s2 (absolute)\n", r.peakFloorAccelerationMps2);
  std::printf("residual roof displacement  %.4g m (after the record + %g s of free vibration)\n\n",
              r.residualRoofDisplacementM, options.freeVibrationSeconds);
  std::printf("storey  peak drift (m)  %speak shear (N)  residual drift (m)\n", heights ? "peak drift ratio  " : "");
  for (std::size_t i = 0; i < n; ++i) {
    if (heights) {
      std::printf("%6zu  %14.6g  %16.6g  %14.7g  %18.4g\n", i + 1, r.peakDriftM[i], r.peakDriftRatio[i],
                  r.peakStoreyShearN[i], r.residualDriftM[i]);
    } else {
      std::printf("%6zu  %14.6g  %14.7g  %18.4g\n", i + 1, r.peakDriftM[i], r.peakStoreyShearN[i], r.residualDriftM[i]);
    }
  }
  return kExitOk;
}

}  // namespace qv::prep

#include "qv/scene/BuildingInfo.h"

#include "qv/core/JsonWriter.h"
#include "qv/format/FacilityCategory.h"
#include "qv/seismic/TypeMixture.h"

namespace qv {

namespace {

// The HAZUS probabilities and consequences of one building (docs/losses.md).
void writeLoss(JsonWriter& w, const BuildingLoss& l) {
  static const char* const states[5] = {"none", "slight", "moderate", "extensive", "complete"};
  w.key("damageProbabilities").beginObject();
  for (std::size_t k = 0; k < 5; ++k) w.field(states[k], l.structural[k]);
  w.endObject();
  w.field("collapseProbability", l.collapse).field("expectedDamageState", l.expectedState());
  std::size_t likely = 0;
  for (std::size_t k = 1; k < 5; ++k) {
    if (l.structural[k] > l.structural[likely]) likely = k;
  }
  w.field("mostLikelyDamageState", states[likely]);
  w.key("consequences").beginObject();
  w.field("occupants", l.occupants).field("occupantsInferred", (l.flags & kLossOccupantsInferred) != 0);
  w.key("injuries").beginArray();
  for (const float v : l.injuries) w.value(v);
  w.endArray();
  w.field("deaths", l.injuries[3]).field("replacementValueUsd", l.replacementValueUsd);
  w.field("valueInferred", (l.flags & kLossValueInferred) != 0).field("repairCostUsd", l.repairCostUsd);
  w.field("repairTimeDays", l.repairTimeDays);
  w.key("tags").beginObject().field("green", l.tag[0]).field("yellow", l.tag[1]).field("red", l.tag[2]).endObject();
  w.endObject();
}

}  // namespace

std::string buildingInfoJson(const BuildingInfo& info) {
  const BuildingAttributes& a = info.attributes;
  JsonWriter w;
  w.beginObject();
  w.field("id", a.id).field("name", a.name).field("use", a.use).field("address", a.address);
  w.field("x", a.centroidX).field("y", a.centroidY);
  w.field("heightM", a.heightM).field("heightSource", valueSourceName(a.heightSource));
  w.field("storeys", static_cast<unsigned>(a.storeys)).field("storeysSource", valueSourceName(a.storeysSource));
  w.field("structuralType", structuralTypeCode(a.structuralType));
  w.field("codeEra", codeEraName(a.codeEra)).field("importance", importanceName(a.importance));
  const FacilityClass facility = classifyFacility(a);
  w.field("facility", facilityCategoryName(facility.category)).field("facilityKind", facility.kind);
  w.field("lod", static_cast<unsigned>(a.lod));
  w.field("damageState", info.hasResponse ? damageStateName(info.response.damage) : std::string_view("no_result"));
  w.key("peakDriftRatio").beginArray();
  for (float d : info.storeyPeakDrift) w.value(d);
  w.endArray();
  if (info.hasResponse && info.response.source != ResponseSource::None) {
    w.field("peakRoofDisplacementM", info.response.peakRoofDisplacementM).field("pgaG", info.response.pgaG);
  } else {
    w.key("peakRoofDisplacementM").null().key("pgaG").null();
  }
  // Informative extras.
  w.field("minHeightM", a.minHeightM).field("footprintAreaM2", a.footprintAreaM2);
  w.field("structuralTypeDescription", structuralTypeDescription(a.structuralType));
  // Where the type is a guess, the damage is the mixture over Hazus types (TypeMixture.h).
  if (const seismic::TypeMixtureInfo m = seismic::buildingTypeMixture(a); !m.shares.empty()) {
    w.key("typeMixture").beginObject().field("source", seismic::kTypeMixtureSource);
    w.field("heightClass", m.heightClass).field("substituted", m.substituted);
    w.key("shares").beginArray();
    for (const seismic::TypeShare& t : m.shares)
      w.beginObject().field("type", t.code).field("share", t.share).endObject();
    w.endArray().endObject();
  } else {
    w.key("typeMixture").null();
  }
  w.key("importanceReasons").beginArray();
  for (const std::string_view name : importanceReasonNames(a.importanceReasons)) w.value(name);
  w.endArray();
  w.field("startYear", static_cast<int>(a.startYear));
  w.field("responseSource", info.hasResponse ? responseSourceName(info.response.source) : std::string_view("none"));
  // Why there is no result (null with a result; "unknown" for responses that did not record it or
  // before the summary loaded), and whether the result is approximate.
  const bool hasResult = info.hasResponse && info.response.source != ResponseSource::None;
  if (hasResult) {
    w.key("noResultReason").null();
  } else {
    w.field("noResultReason",
            noResultReasonName(info.hasResponse ? info.response.noResultReason : NoResultReason::Unknown));
  }
  w.field("approximate", hasResult && info.response.approximate);
  w.field("unconvergedSteps", hasResult ? info.response.unconvergedSteps : 0u);
  w.field("worstResidualRatio", hasResult ? info.response.worstResidualRatio : 0.0f);
  if (!info.modelSource.empty()) {
    w.field("modelSource", info.modelSource);
    w.field("modelTriangles", info.modelTriangles);
  }
  w.field("detailed", info.detailed).field("tile", info.tile);
  // The field's shaking at the site (null where the field gives none); pgaG above is the record's.
  if (info.hasResponse && hasResult) w.field("recordPgaG", info.response.pgaG);
  if (info.site) {
    const BuildingSite& s = *info.site;
    w.key("siteShaking").beginObject().field("source", siteSourceName(s.source));
    w.field("pgaG", s.pgaG).field("pgvCmS", s.pgvCmS).field("psa03G", s.psa03G).field("psa10G", s.psa10G);
    w.field("psa30G", s.psa30G).field("mmi", s.mmi).field("vs30Mps", s.vs30Mps).endObject();
  } else {
    w.key("siteShaking").null();
  }
  if (hasResult && info.scaling) {
    w.key("spectralScaling").beginObject();
    for (int d = 0; d < 2; ++d) {
      w.key(d == 0 ? "x" : "y").beginObject();
      w.field("periodS", info.scaling->periodS[d]).field("targetSaG", info.scaling->targetSaG[d]);
      w.field("recordSaG", info.scaling->recordSaG[d]).field("scale", info.scaling->scale[d]).endObject();
    }
    w.endObject();
  }
  if (hasResult && info.spread) {
    w.key("suite").beginObject().field("records", static_cast<unsigned>(info.spread->records));
    w.field("shownRecord", static_cast<unsigned>(info.spread->shownRecord));
    w.field("driftBeta", info.spread->driftBeta).field("accelerationBeta", info.spread->accelerationBeta).endObject();
  }
  if (hasResult && info.loss) writeLoss(w, *info.loss);
  w.endObject();
  return w.take();
}

}  // namespace qv

#include "qv/scene/FrameStats.h"

namespace qv {

FrameStats::FrameStats(std::size_t window)
    : interval_(window),
      cull_(window),
      lod_(window),
      animate_(window),
      upload_(window),
      render_(window),
      total_(window),
      drawCalls_(window),
      triangles_(window),
      upload_bytes_(window) {}

void FrameStats::record(double intervalSeconds, const FrameTimesMs& t, const FrameCounts& c) {
  if (intervalSeconds > 0.0) interval_.add(intervalSeconds);
  cull_.add(t.cull);
  lod_.add(t.lod);
  animate_.add(t.animate);
  upload_.add(t.upload);
  render_.add(t.render);
  total_.add(t.total);
  drawCalls_.add(c.drawCalls);
  triangles_.add(static_cast<double>(c.triangles));
  upload_bytes_.add(static_cast<double>(c.uploadBytes));
  latest_ = c;
  ++frames_;
}

StatsSummary FrameStats::summary() const {
  StatsSummary s;
  const double interval = interval_.median();
  s.fps = interval > 0.0 ? 1.0 / interval : 0.0;
  s.frameMs = {cull_.median(), lod_.median(), animate_.median(), upload_.median(), render_.median(), total_.median()};
  s.frameMsP95 = {cull_.percentile(0.95),   lod_.percentile(0.95),    animate_.percentile(0.95),
                  upload_.percentile(0.95), render_.percentile(0.95), total_.percentile(0.95)};
  s.drawCalls = drawCalls_.median();
  s.triangles = triangles_.median();
  s.uploadBytes = upload_bytes_.median();
  s.latest = latest_;
  return s;
}

void FrameStats::clear() {
  for (RollingStats* r :
       {&interval_, &cull_, &lod_, &animate_, &upload_, &render_, &total_, &drawCalls_, &triangles_, &upload_bytes_}) {
    r->clear();
  }
  frames_ = 0;
}

}  // namespace qv

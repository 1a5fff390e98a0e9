#include "engine/core/dataset.h"

#include <cmath>
#include <cstring>
#include <sstream>

#include "engine/core/digest.h"
#include "engine/core/error.h"

namespace recon {

int64_t DataSpec::YSize() const {
  int64_t n = y_shape.empty() ? 0 : 1;
  for (int64_t d : y_shape) n *= d;
  return n;
}

std::string DataSpec::ToString() const {
  std::ostringstream out;
  out << "x " << x_dim << ", y ";
  for (size_t i = 0; i < y_shape.size(); ++i) out << (i ? "x" : "") << y_shape[i];
  out << ", b " << b_dim << ", u " << u_dim;
  return out.str();
}

int64_t Dataset::NumDemoSamples() const {
  int64_t n = 0;
  for (const Episode& e : demos) n += static_cast<int64_t>(e.samples.size());
  return n;
}

namespace {

void CheckField(const std::vector<float>& values, int64_t expected, const std::string& where,
                const char* field) {
  if (static_cast<int64_t>(values.size()) != expected) {
    std::ostringstream msg;
    msg << where << ": field '" << field << "' has " << values.size() << " values, expected "
        << expected;
    throw UserError(msg.str());
  }
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      std::ostringstream msg;
      msg << where << ": field '" << field << "' element " << i << " is not finite (" << values[i]
          << ")";
      throw UserError(msg.str());
    }
  }
}

}  // namespace

void ValidateDataset(const Dataset& dataset, const std::string& source) {
  const DataSpec& s = dataset.spec;
  if (s.x_dim < 0 || s.u_dim <= 0 || s.b_dim < 0 || s.YSize() <= 0) {
    throw UserError(source + ": invalid data spec (" + s.ToString() + ")");
  }
  if (dataset.demos.empty()) {
    throw UserError(source + ": no demonstrations (at least one is needed to learn a policy)");
  }
  for (size_t e = 0; e < dataset.demos.size(); ++e) {
    const Episode& episode = dataset.demos[e];
    if (episode.samples.empty()) {
      throw UserError(source + ": demonstration " + std::to_string(e) + " has no samples");
    }
    for (size_t t = 0; t < episode.samples.size(); ++t) {
      const Sample& sample = episode.samples[t];
      const std::string where =
          source + ": demonstration " + std::to_string(e) + ", sample " + std::to_string(t);
      CheckField(sample.x, s.x_dim, where, "x");
      CheckField(sample.y, s.YSize(), where, "y");
      CheckField(sample.b, s.b_dim, where, "b");
      CheckField(sample.u, s.u_dim, where, "u");
    }
  }
  if (!dataset.play_chunks.empty()) {
    int64_t total = 0;
    for (int size : dataset.play_chunks) {
      if (size < 0) throw UserError(source + ": a play chunk has a negative size");
      total += size;
    }
    if (total != static_cast<int64_t>(dataset.play.size())) {
      throw UserError(source + ": the play chunks hold " + std::to_string(total) +
                      " samples, but there are " + std::to_string(dataset.play.size()));
    }
  }
  for (size_t p = 0; p < dataset.play.size(); ++p) {
    const PlaySample& sample = dataset.play[p];
    const std::string where = source + ": play sample " + std::to_string(p);
    CheckField(sample.x, s.x_dim, where, "x");
    CheckField(sample.y, s.YSize(), where, "y");
    CheckField(sample.b, s.b_dim, where, "b");
  }
}

namespace {

class FingerprintHash {
 public:
  void Add(const void* data, size_t size) { hash_ = recon::Fnv1a(data, size, hash_); }
  void Add(const std::vector<float>& v) {
    const uint64_t n = v.size();
    Add(&n, sizeof(n));
    Add(v.data(), v.size() * sizeof(float));
  }
  void Add(int64_t v) { Add(&v, sizeof(v)); }
  uint64_t hash() const { return hash_; }

 private:
  uint64_t hash_ = kFnv1aOffset;
};

}  // namespace

uint64_t Fingerprint(const Dataset& dataset) {
  FingerprintHash h;
  const DataSpec& s = dataset.spec;
  h.Add(s.x_dim);
  for (int64_t d : s.y_shape) h.Add(d);
  h.Add(s.b_dim);
  h.Add(s.u_dim);
  h.Add(static_cast<int64_t>(dataset.demos.size()));
  for (const Episode& e : dataset.demos) {
    h.Add(static_cast<int64_t>(e.samples.size()));
    for (const Sample& sample : e.samples) {
      h.Add(sample.x);
      h.Add(sample.y);
      h.Add(sample.b);
      h.Add(sample.u);
    }
  }
  h.Add(static_cast<int64_t>(dataset.play.size()));
  for (const PlaySample& p : dataset.play) {
    h.Add(p.x);
    h.Add(p.y);
    h.Add(p.b);
  }
  return h.hash();
}

}  // namespace recon

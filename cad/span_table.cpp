#include "cad/span_table.h"

#include <Geom_RectangularTrimmedSurface.hxx>
#include <Standard_Failure.hxx>

#include <algorithm>

namespace sizemesh {

namespace {

Handle(Geom_BSplineSurface) bspline_of(Handle(Geom_Surface) s) {
  while (const auto t = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = t->BasisSurface();
  return Handle(Geom_BSplineSurface)::DownCast(s);
}

std::vector<double> to_vector(const TColStd_Array1OfReal& a) {
  std::vector<double> out;
  out.reserve(a.Length());
  for (int i = a.Lower(); i <= a.Upper(); ++i) out.push_back(a.Value(i));
  return out;
}

}  // namespace

std::unique_ptr<SpanTable> SpanTable::make(const Handle(Geom_Surface)& s, size_t max_bytes) {
  const Handle(Geom_BSplineSurface) b = bspline_of(s);
  if (b.IsNull()) return nullptr;
  try {
    std::unique_ptr<SpanTable> t(new SpanTable(b));
    if (t->nu_ < 1 || t->nv_ < 1 || t->bytes_ > max_bytes) return nullptr;
    t->spans_.reset(new std::atomic<BSplSLib_Cache*>[static_cast<size_t>(t->nu_) * t->nv_]);
    for (size_t i = 0; i < static_cast<size_t>(t->nu_) * t->nv_; ++i) t->spans_[i] = nullptr;
    return t;
  } catch (const Standard_Failure&) {
    return nullptr;
  }
}

SpanTable::SpanTable(const Handle(Geom_BSplineSurface)& s)
    : s_(s),
      pu_(s->UDegree(), s->IsUPeriodic(), s->UKnotSequence()),
      pv_(s->VDegree(), s->IsVPeriodic(), s->VKnotSequence()),
      ku_(to_vector(s->UKnotSequence())),
      kv_(to_vector(s->VKnotSequence())),
      lower_u_(s->UKnotSequence().Lower()),
      lower_v_(s->VKnotSequence().Lower()),
      nu_(pu_.SpanIndexMax - pu_.SpanIndexMin + 1),
      nv_(pv_.SpanIndexMax - pv_.SpanIndexMin + 1) {
  // A span's polynomial: (p + 1)(q + 1) coefficients of 3 or 4 reals, plus the
  // cache object and its pointer.
  const size_t per = static_cast<size_t>(s->UDegree() + 1) * (s->VDegree() + 1) * (s->IsURational() || s->IsVRational() ? 4 : 3) *
                         sizeof(double) + 160 + sizeof(void*);
  bytes_ = std::max(0, nu_) * static_cast<size_t>(std::max(0, nv_)) * per;
}

SpanTable::~SpanTable() {
  if (!spans_) return;
  for (size_t i = 0; i < static_cast<size_t>(nu_) * nv_; ++i) delete spans_[i].load();
}

// The span [k_i, k_i+1) holding t (the first or last span past the ends), as
// BSplSLib_Cache::IsCacheValid reads it; 0-based from SpanIndexMin.
int SpanTable::locate(const BSplCLib_CacheParams& p, const std::vector<double>& k, int lower, double t) {
  const double x = p.PeriodicNormalization(t);
  const int lo = p.SpanIndexMin - lower, hi = p.SpanIndexMax - lower;
  const int i = static_cast<int>(std::upper_bound(k.begin() + lo, k.begin() + hi + 1, x) - k.begin()) - 1;
  return std::clamp(i, lo, hi) - lo;
}

const BSplSLib_Cache* SpanTable::span(double u, double v) const {
  const int iu = locate(pu_, ku_, lower_u_, u), iv = locate(pv_, kv_, lower_v_, v);
  std::atomic<BSplSLib_Cache*>& slot = spans_[static_cast<size_t>(iu) * nv_ + iv];
  if (BSplSLib_Cache* c = slot.load(std::memory_order_acquire)) return c;
  const int ju = iu + pu_.SpanIndexMin - lower_u_, jv = iv + pv_.SpanIndexMin - lower_v_;
  const double u0 = ku_[ju], u1 = ku_[ju + 1], v0 = kv_[jv], v1 = kv_[jv + 1];
  if (!(u1 > u0) || !(v1 > v0)) return nullptr;
  auto* made = new BSplSLib_Cache(s_->UDegree(), s_->IsUPeriodic(), s_->UKnotSequence(), s_->VDegree(),
                                  s_->IsVPeriodic(), s_->VKnotSequence(), s_->Weights());
  made->BuildCache(0.5 * (u0 + u1), 0.5 * (v0 + v1), s_->UKnotSequence(), s_->VKnotSequence(), s_->Poles(),
                   s_->Weights());
  BSplSLib_Cache* expected = nullptr;
  if (slot.compare_exchange_strong(expected, made, std::memory_order_acq_rel)) return made;
  delete made;  // another thread built it first
  return expected;
}

bool SpanTable::d1(double u, double v, gp_Pnt& p, gp_Vec& du, gp_Vec& dv) const {
  const BSplSLib_Cache* c = span(u, v);
  if (!c) return false;
  c->D1(u, v, p, du, dv);
  return true;
}

}  // namespace sizemesh

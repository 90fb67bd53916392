// Fuzz target: the SRDF reader (dss::parseSrdf), then every group it declares expanded against
// our arm (dss::groupActiveJoints), the SRDF checked against the arm's model and its disabled
// pairs applied to the self-collision pairs. Any bytes must end in an Srdf or a
// std::exception naming the source; an expanded group must list increasing, in-range active
// joint indices.
#include <cstdint>
#include <exception>
#include <string>

#include "dss/robot/collision_pairs.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "fuzz_support.h"

namespace {

const dss::RobotModel& arm() {
  static const dss::RobotModel model = [] {
    dss::LoadOptions options;
    options.load_collisions = true;
    return dss::loadUrdf(dss_fuzz::armDir() + "/dss_arm7.urdf", options);
  }();
  return model;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  (void)arm();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  dss::Srdf srdf;
  try {
    srdf = dss::parseSrdf(text, "fuzz.srdf");
  } catch (const std::exception&) {
    return 0;
  }
  const dss::RobotModel& model = arm();
  for (const dss::SrdfGroup& g : srdf.groups) {
    try {
      const std::vector<int> active = dss::groupActiveJoints(model, srdf, g.name);
      for (std::size_t i = 0; i < active.size(); ++i)
        if (active[i] < 0 || active[i] >= static_cast<int>(model.numActiveJoints()) ||
            (i > 0 && active[i] <= active[i - 1]))
          dss_fuzz::propertyFailed("group " + g.name + ": active joints not increasing in range");
    } catch (const std::exception&) {
    }
  }
  (void)dss::checkSrdfAgainstModel(model, srdf);
  try {
    (void)dss::selfCollisionPairs(model, &srdf);
  } catch (const std::exception&) {
  }
  return 0;
}

// SPDX-License-Identifier: Apache-2.0
#include "core/detector.h"

namespace phasor {

ParamSpec ResponseParam(const char *defaultResponse) {
    return P::String("response", "sensor response: CIE XYZ (RGB output) or flat radiometric")
        .Default(Value::String(defaultResponse))
        .Choices({"cie_xyz", "radiometric"});
}

SensorResponse ResponseFromParams(const ParamDict &d) {
    return SensorResponse(d.GetString("response") == "radiometric" ? SensorResponse::Kind::Radiometric
                                                                   : SensorResponse::Kind::CieXyz);
}

}  // namespace phasor

#pragma once
// The tone curves of preview.png (RenderSettings::tonemap), on linear radiance.
namespace headlight {

float tonemapAces(float x);      // Narkowicz's fit of the ACES filmic curve
float tonemapReinhard(float x);  // x / (1 + x)

}  // namespace headlight

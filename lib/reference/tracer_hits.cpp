// What the reference tracer's rays meet (Tracer, pixel_tracer.hpp): the
// blended layers composited along a primary ray, the radiance leaving a hit,
// direct light with shadow rays, and the sky ambient and environment map
// sampled with true visibility. tracer.cpp holds the per-pixel path.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "reference/lobe_clearcoat.hpp"
#include "reference/lobe_specular.hpp"
#include "reference/lobe_transmission.hpp"
#include "reference/pixel_tracer.hpp"
#include "reference/shading.hpp"
#include "reference/texture_sampler.hpp"
#include "reference/transmission_trace.hpp"

namespace headlight::reference {

namespace {

// Blended layers composited along one primary ray, nearest first; more are
// ignored (32 layers of alpha 0.1 leave 3 % of what is behind).
constexpr int kMaxBlendLayers = 32;

// The triangle a ray met: its corners' indices and world positions, the
// barycentrics, and the face normal (unnormalised; glTF's front face is
// counter-clockwise, flipped with the instance's winding) and whether the
// ray meets that front.
struct HitTriangle {
  const std::uint32_t* corner;
  float u, v, w;
  glm::vec3 p0, p1, p2;
  glm::vec3 faceNormal;
  bool front;
};

HitTriangle hitTriangle(const InstanceShading& instance, const RTCHit& hit, const glm::vec3& rayDirection) {
  HitTriangle triangle;
  triangle.corner = &instance.primitive->indices[std::size_t(hit.primID) * 3];
  triangle.u = hit.u, triangle.v = hit.v, triangle.w = 1.0f - hit.u - hit.v;
  auto world = [&](std::uint32_t index) {
    const float* p = &instance.worldPositions[std::size_t(index) * 3];
    return glm::vec3(p[0], p[1], p[2]);
  };
  triangle.p0 = world(triangle.corner[0]), triangle.p1 = world(triangle.corner[1]);
  triangle.p2 = world(triangle.corner[2]);
  triangle.faceNormal = glm::cross(triangle.p1 - triangle.p0, triangle.p2 - triangle.p0) * instance.frontSign;
  triangle.front = glm::dot(triangle.faceNormal, rayDirection) <= 0.0f;
  return triangle;
}

}  // namespace

// alphaMode BLEND along the primary ray: every blended layer in front of
// the G-buffer's surface (`opaque`; null on background) is shaded and
// composited over `lit` back to front, colour a L + (1 - a) behind and
// alpha a + (1 - a) behind, as the blend pass does, but in the exact
// order of the hits (no per-instance sort).
void Tracer::compositeBlended(int x, int y, const glm::vec3* opaque, float* lit, Pcg32& random) {
  const auto [origin, direction] = primaryRay(x, y);
  if (!isFinite(origin) || !isFinite(direction)) return;
  const float limit = opaque ? glm::dot(*opaque - origin, direction) - in_.epsilon
                             : std::numeric_limits<float>::infinity();
  if (!(limit > 0.0f)) return;
  struct Layer {
    glm::vec3 radiance;
    float alpha;
  };
  std::vector<Layer> layers;
  float tnear = 0.0f;
  for (int i = 0; i < kMaxBlendLayers; ++i) {
    RTCRayHit rayHit = makeRayHit(origin, direction, limit);
    rayHit.ray.tnear = tnear;
    rtcIntersect1(in_.blendedScene, &context_, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    tnear = std::nextafter(rayHit.ray.tfar, std::numeric_limits<float>::infinity());
    Layer layer;
    if (shadeBlendedHit(rayHit, direction, random, layer.radiance, layer.alpha)) layers.push_back(layer);
  }
  glm::vec3 color(lit[0], lit[1], lit[2]);
  float coverage = lit[3];
  for (auto layer = layers.rbegin(); layer != layers.rend(); ++layer) {
    color = layer->alpha * layer->radiance + (1.0f - layer->alpha) * color;
    coverage = layer->alpha + (1.0f - layer->alpha) * coverage;
  }
  lit[0] = color.r, lit[1] = color.g, lit[2] = color.b, lit[3] = coverage;
}

// One blended layer: its alpha and the radiance it sends along the ray
// (emission, direct light with shadow rays, sky ambient with true
// visibility and one-bounce indirect, from the same cosine rays as a
// G-buffer pixel). False for the back of a single-sided surface, which
// the rasteriser culls. Normal maps are not read (as radianceLeaving).
bool Tracer::shadeBlendedHit(const RTCRayHit& rayHit, const glm::vec3& rayDirection, Pcg32& random, glm::vec3& radiance,
                             float& alpha, int rays) {
  const InstanceShading& instance = in_.instances[rayHit.hit.geomID];
  const Primitive& primitive = *instance.primitive;
  const Material& material = *instance.material;
  const HitTriangle hit = hitTriangle(instance, rayHit.hit, rayDirection);
  const std::uint32_t* corner = hit.corner;
  const float u = hit.u, v = hit.v, w = hit.w;
  const bool front = hit.front;
  if (!front && !material.doubleSided) return false;
  glm::vec3 normal = instance.normalFromLocal * (w * primitive.normals[corner[0]] + u * primitive.normals[corner[1]] +
                                                 v * primitive.normals[corner[2]]);
  const float normalLength = glm::length(normal);
  normal = normalLength > 0.0f ? normal / normalLength : -rayDirection;
  if (!front) normal = -normal;

  glm::vec4 baseColor = material.baseColorFactor;
  float metallic = material.metallicFactor, roughness = material.roughnessFactor;
  glm::vec3 emission = material.emissiveFactor;
  const bool textured = !primitive.texcoords.empty();
  glm::vec2 uv(0.0f);
  if (textured)
    uv = w * primitive.texcoords[corner[0]] + u * primitive.texcoords[corner[1]] + v * primitive.texcoords[corner[2]];
  if (textured && material.baseColorTexture.present())
    baseColor *= sampleTexture(in_.scene, material.baseColorTexture, uv, true);
  if (!primitive.colors.empty())
    baseColor *= w * primitive.colors[corner[0]] + u * primitive.colors[corner[1]] + v * primitive.colors[corner[2]];
  if (textured && material.metallicRoughnessTexture.present()) {
    const glm::vec4 texel = sampleTexture(in_.scene, material.metallicRoughnessTexture, uv, false);
    if (material.roughnessFromGlossiness) {
      roughness = 1.0f - roughness * texel.a;  // as gbuffer.frag: glossiness in A, metallic the factor
    } else {
      roughness *= texel.g;
      metallic *= texel.b;
    }
  }
  if (textured && material.emissiveTexture.present() && material.emissive())
    emission *= glm::vec3(sampleTexture(in_.scene, material.emissiveTexture, uv, true));
  alpha = std::clamp(baseColor.a, 0.0f, 1.0f);  // as blend.glsl
  // An opaque KHR_materials_unlit surface (seen through glass) shows its base
  // colour, as the composite writes it; the blend pass lights blended ones.
  if (material.unlit && !material.blended()) {
    radiance = glm::vec3(baseColor);
    return true;
  }
  metallic = std::clamp(metallic, 0.0f, 1.0f);
  roughness = std::clamp(roughness, 0.0f, 1.0f);

  const glm::vec3 position = w * hit.p0 + u * hit.p1 + v * hit.p2;
  const glm::vec3 view = -rayDirection;
  const glm::vec3 origin = position + normal * in_.epsilon;
  const Basis basis = basisAround(normal);
  const glm::vec3 diffuseWeight = (1.0f - metallic) * glm::vec3(baseColor);
  Surface surface = makeSurface(glm::vec3(baseColor), metallic, roughness, normal, view);
  // The lobes from the material, as blend.glsl has them (no normal map: the coat's normal is the surface's).
  auto texel = [&](const TextureRef& ref, bool srgb) {
    return textured && ref.present() ? sampleTexture(in_.scene, ref, textureUv(primitive, ref, corner, u, v), srgb)
                                     : glm::vec4(1.0f);
  };
  applyMaterialLobes(surface, material, texel);
  const int n = rays > 0 ? rays : in_.settings.samplesPerPixel;
  glm::dvec3 skySum(0.0), indirectSum(0.0);
  for (int i = 0; i < n; ++i) {
    const float xi0 = random.uniform(), xi1 = random.uniform();
    const glm::vec3 direction = basis.toWorld(cosineSampleHemisphere(xi0, xi1));
    // Through glass as the pixel's own cosine rays (tracer.cpp); the sky
    // under the layers over the base (sheen) as there, the indirect light not.
    const PassedHit bounce = pastTransmissive(origin, direction, traceFromSurface(origin, direction, view));
    const float layers = layerScaleToward(surface, direction);
    if (bounce.hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      skySum += glm::dvec3(bounce.transmittance * skyRadiance(in_.scene.sky, direction) * layers);
    else
      indirectSum += glm::dvec3(bounce.transmittance * diffuseWeight * radianceLeaving(bounce.hit, direction));
  }
  Clearcoat coat;
  if (const std::optional<MaterialClearcoat>& clearcoat = material.clearcoat)
    coat = makeClearcoat(clearcoatLobeOfMaterial(*clearcoat, texel(clearcoat->clearcoatTexture, false),
                                                 texel(clearcoat->clearcoatRoughnessTexture, false), normal),
                         view);
  const glm::vec3 under = emission +
                          ambientLight(surface, origin, basis, glm::vec3(skySum / double(n)), random, nullptr, nullptr,
                                       rays > 0 ? std::max(rays / 4, 1) : 0) +
                          glm::vec3(indirectSum / double(n));
  radiance = directLight(surface, position, origin, coat) +
             clearcoatLayer(coat, under, coatAmbient(coat, view, origin, random));
  return true;
}

// Fraction of a light's radiance that arrives, per channel: 1, 0 behind an
// occluder, tinted behind transmissive surfaces (the renderer's
// transmittance maps). Lights that cast no shadow in the renderer cast
// none here either.
glm::vec3 Tracer::lightVisibility(const Light& light, const glm::vec3& origin, const glm::vec3& toLight,
                                  float distance) {
  if (!light.castsShadows) return glm::vec3(1.0f);
  // Stop short of a point or spot light by epsilon: geometry at the light's
  // position (a bulb's own mesh) must not shadow it.
  const float far = std::isfinite(distance) ? std::max(distance - in_.epsilon, 0.0f) : distance;
  if (!in_.transmissiveScene) return glm::vec3(unoccluded(origin, toLight, far) ? 1.0f : 0.0f);
  if (!isFinite(origin) || !isFinite(toLight)) return glm::vec3(0.0f);  // as unoccluded: Embree asserts on them
  return shadowRayTransmittance(in_.scene, in_.instances, in_.rtcScene, context_, light, origin, toLight, far);
}

// direct_light.frag with shadow rays from `origin` for the maps, the coat
// layered per light; a transmissive surface's as transmission.glsl's, a
// light behind it seen through it with its shadow ray from the back.
glm::vec3 Tracer::directLight(const Surface& surface, const glm::vec3& position, const glm::vec3& origin,
                              const Clearcoat& coat, const TransmissiveSurface& transmissive) {
  glm::vec3 sum(0.0f);
  for (const Light& light : in_.scene.lights) {
    glm::vec3 toLight;
    float distance;
    const float attenuation = lightAttenuation(light, position, toLight, distance);
    if (attenuation <= 0.0f) continue;
    const glm::vec3 base = transmissive.share > 0.0f ? transmissiveCookTorrance(surface, toLight, transmissive.blur)
                                                     : cookTorrance(surface, toLight);
    const glm::vec3 brdf = clearcoatLayer(coat, base, glm::vec3(clearcoatSpecular(coat, surface.view, toLight)));
    if (brdf == glm::vec3(0.0f)) continue;
    const bool behind = glm::dot(surface.normal, toLight) < 0.0f;
    const glm::vec3 from = behind ? position - surface.normal * in_.epsilon : origin;
    const glm::vec3 visibility = lightVisibility(light, from, toLight, distance);
    sum += brdf * light.color * light.intensity * (attenuation * visibility);
  }
  return sum;
}

// Sky ambient with true visibility. Diffuse: the cosine rays' mean sky
// radiance over escaped rays (`skyMean`, 0 for blocked ones) is E / pi.
// Specular: GGX-importance-sampled reflections, each weighted by
// BRDF * N.L / pdf = F * 4 Vis V.H N.L / N.H (as brdf_lut.frag), times the
// sky when the ray escapes. The same samples' Fresnel-free weights give
// the split-sum scale and bias, hence the renderer's diffuse weight
// kd = (1 - (f0 scale + bias)) (1 - metallic) without its 64x64 table.
// Anisotropy: the half vectors come from the stretched lobe, in its frame
// (T, B, N), with its visibility (the lobes' stretchedGgx hook). Layers
// (sheen): each direction's base term is scaled by them (baseLayerScale),
// and their own light is estimated by layersAmbient. The share of the lobe's Fresnel-free weight that
// escapes is the specular sky visibility (ao_ref's specular.Y, compared with
// the SSGI's specular.Y).
glm::vec3 Tracer::ambientLight(const Surface& surface, const glm::vec3& origin, const Basis& basis,
                               const glm::vec3& skyMean, Pcg32& random, glm::vec3* specularAlbedoOut,
                               float* specularVisibilityOut, int specularRays) {
  const int m = specularRays > 0 ? specularRays : in_.specularSamples;
  const float alpha = surface.roughness * surface.roughness;
  const std::optional<StretchedGgx> stretchedGgx = lobesStretchedGgx(surface, alpha);
  const bool stretched = stretchedGgx.has_value();
  const Basis frame =
      stretched ? Basis{stretchedGgx->tangent, glm::cross(surface.normal, stretchedGgx->tangent), surface.normal}
                : basis;
  const float alphaT = stretched ? stretchedGgx->alphaT : alpha, alphaB = stretched ? stretchedGgx->alphaB : alpha;
  auto inFrame = [&](const glm::vec3& v, float nDot) {
    return glm::vec3(glm::dot(frame.tangent, v), glm::dot(frame.bitangent, v), nDot);
  };
  double scale = 0.0, bias = 0.0;
  // specular.Y: the Fresnel-free weight of the samples that escape over all of it.
  double escapedWeight = 0.0, lobeWeight = 0.0;
  glm::dvec3 specular(0.0);
  for (int j = 0; j < m; ++j) {
    const float xi0 = random.uniform(), xi1 = random.uniform();
    const glm::vec3 halfVector = frame.toWorld(stretched ? importanceSampleAnisotropicGgx(xi0, xi1, alphaT, alphaB)
                                                         : importanceSampleGgx(xi0, xi1, alpha));
    const float vDotHRaw = glm::dot(surface.view, halfVector);
    const glm::vec3 toLight = 2.0f * vDotHRaw * halfVector - surface.view;  // reflect(-V, H)
    const float nDotL = glm::dot(surface.normal, toLight);
    if (nDotL <= 0.0f) continue;
    const float nDotH = std::max(glm::dot(surface.normal, halfVector), 0.0f);
    const float vDotH = std::max(vDotHRaw, 0.0f);
    const float visibility =
        stretched ? anisotropicVisibility(alphaT, alphaB, inFrame(surface.view, surface.nDotV), inFrame(toLight, nDotL))
                  : smithGgxVisibility(surface.nDotV, nDotL, alpha);
    const float weight = 4.0f * visibility * vDotH * nDotL / std::max(nDotH, 1e-7f);
    const float fresnel = std::pow(1.0f - vDotH, 5.0f);
    scale += (1.0f - fresnel) * weight;
    bias += fresnel * weight;
    lobeWeight += weight;
    const glm::vec3 direction = glm::normalize(toLight);
    // The lobes' Fresnel (an iridescent film's, one value per pixel) over Schlick's, as cookTorrance.
    const glm::vec3 sampleFresnel = lobesFresnel(surface, surface.f0 * (1.0f - fresnel) + surface.f90 * fresnel);
    if (unoccluded(origin, direction, std::numeric_limits<float>::infinity())) {
      specular +=
          glm::dvec3(sampleFresnel * weight * ambientRadiance(direction) * layerScaleToward(surface, direction));
      escapedWeight += weight;
    }
  }
  if (specularVisibilityOut && lobeWeight > 0.0) *specularVisibilityOut = float(escapedWeight / lobeWeight);
  // At most 1: the sampled scale + bias can pass it at grazing angles (exactly, and in the renderer's
  // table, it cannot), and 1 - it weighs the diffuse lobe and what glass lets through (an iridescent
  // glass rim's reference pixel came out at -0.035).
  const glm::vec3 specularAlbedo =
      glm::min(lobesSpecularAlbedo(surface, surface.f0 * float(scale / m) + surface.f90 * float(bias / m),
                                   glm::vec2(float(scale / m), float(bias / m))),
               glm::vec3(1.0f));
  if (specularAlbedoOut) *specularAlbedoOut = specularAlbedo;
  const glm::vec3 diffuseWeight = (1.0f - specularAlbedo) * (1.0f - surface.metallic) * (1.0f - surface.transmission);
  glm::vec3 ambient = diffuseWeight * surface.albedo * skyMean + glm::vec3(specular / double(m));
  if (hasLayerLight(surface)) ambient += layersAmbient(surface, origin, basis, random);
  return ambient * in_.skyIntensity;
}

// The layers' own light (sheen's) under the ambient with true visibility:
// `m` directions uniform over the hemisphere (density 1 / 2 pi), each adding
// the layers' light (f N.L, layersLight) L 2 pi where it escapes.
glm::vec3 Tracer::layersAmbient(const Surface& surface, const glm::vec3& origin, const Basis& basis, Pcg32& random) {
  const int m = in_.specularSamples;
  glm::dvec3 sum(0.0);
  for (int j = 0; j < m; ++j) {
    const float cosTheta = random.uniform(), phi = 2.0f * kPi * random.uniform();
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const glm::vec3 direction = basis.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    if (cosTheta <= 0.0f || !unoccluded(origin, direction, std::numeric_limits<float>::infinity())) continue;
    const float nDotH = std::max(glm::dot(surface.normal, glm::normalize(direction + surface.view)), 0.0f);
    sum += glm::dvec3(layersLight(surface, cosTheta, nDotH) * ambientRadiance(direction));
  }
  return glm::vec3(sum * double(2.0f * kPi) / double(m));
}

// E / pi from the environment map with true visibility, by importance
// sampling the map (environment_sampler.hpp): each of `count` directions
// drawn in proportion to the map's luminance adds L V cos / (pi pdf).
// Cosine-weighted rays would rarely find a small bright source.
// Each direction's light is scaled by the sheen layer above the base (1 without).
glm::vec3 Tracer::environmentIrradianceOverPi(const Surface& surface, const glm::vec3& origin, int count,
                                              Pcg32& random) {
  const glm::vec3& normal = surface.normal;
  const EnvironmentLight& light = *in_.environment;
  glm::dvec3 sum(0.0);
  for (int i = 0; i < count; ++i) {
    const float xi0 = random.uniform(), xi1 = random.uniform();
    float pdf = 0.0f;
    const glm::vec3 mapDirection = light.sampler.sample(xi0, xi1, pdf);
    const glm::vec3 direction = environment::mapToWorld(mapDirection, light.cosRotation, light.sinRotation);
    const float cosine = glm::dot(normal, direction);
    if (cosine <= 0.0f || pdf <= 0.0f) continue;
    if (!unoccluded(origin, direction, std::numeric_limits<float>::infinity())) continue;
    sum += glm::dvec3(light.map.lookup(mapDirection)) *
           double(cosine * layerScaleToward(surface, direction) / (kPi * pdf));
  }
  return glm::vec3(sum / double(count));
}

// Ld(h): the Lambertian radiance that the hit surface sends back along the
// ray (direct punctual light with shadow rays, plus its emission). The
// back of a single-sided surface is black: the renderer never draws it,
// but it still blocks rays as its shadow maps do.
glm::vec3 Tracer::radianceLeaving(const RTCRayHit& rayHit, const glm::vec3& rayDirection) {
  const InstanceShading& instance = in_.instances[rayHit.hit.geomID];
  const Primitive& primitive = *instance.primitive;
  const Material& material = *instance.material;
  const HitTriangle hit = hitTriangle(instance, rayHit.hit, rayDirection);
  const std::uint32_t* corner = hit.corner;
  const float u = hit.u, v = hit.v, w = hit.w;
  const bool front = hit.front;
  if (!front && !material.doubleSided) return glm::vec3(0.0f);
  glm::vec3 faceNormal = hit.faceNormal;
  if (!front) faceNormal = -faceNormal;
  const float faceLength = glm::length(faceNormal);
  // Degenerate triangles have no face normal; the ray's own direction
  // gives the side it came from.
  const glm::vec3 towardOrigin = faceLength > 0.0f ? faceNormal / faceLength : -rayDirection;

  const glm::vec3 localNormal =
      w * primitive.normals[corner[0]] + u * primitive.normals[corner[1]] + v * primitive.normals[corner[2]];
  glm::vec3 normal = instance.normalFromLocal * localNormal;
  const float normalLength = glm::length(normal);
  normal = normalLength > 0.0f ? normal / normalLength : towardOrigin;
  if (!front) normal = -normal;  // gbuffer.frag: the back of a double-sided surface faces the other way

  glm::vec3 baseColor(material.baseColorFactor);
  float metallic = material.metallicFactor;
  glm::vec3 emissive = material.emissiveFactor;
  // gbuffer.frag samples textures only where the primitive has texcoords.
  const bool textured = !primitive.texcoords.empty();
  auto sample = [&](const TextureRef& ref, bool srgb) {
    return sampleTexture(in_.scene, ref, textureUv(primitive, ref, corner, u, v), srgb);
  };
  if (textured && material.baseColorTexture.present())
    baseColor *= glm::vec3(sample(material.baseColorTexture, true));
  if (!primitive.colors.empty())  // COLOR_0, as gbuffer.frag multiplies it
    baseColor *= glm::vec3(w * primitive.colors[corner[0]] + u * primitive.colors[corner[1]] +
                           v * primitive.colors[corner[2]]);
  // KHR_materials_unlit: the surface shows its base colour, as the
  // composite writes it, whatever lights it.
  if (material.unlit) return baseColor;
  if (textured && material.metallicRoughnessTexture.present() && !material.roughnessFromGlossiness)
    metallic *= sample(material.metallicRoughnessTexture, false).b;
  if (textured && material.emissiveTexture.present() && material.emissive())
    emissive *= glm::vec3(sample(material.emissiveTexture, true));
  metallic = std::clamp(metallic, 0.0f, 1.0f);

  const glm::vec3 diffuse = (1.0f - metallic) * baseColor / kPi;
  glm::vec3 radiance = emissive;
  if (diffuse == glm::vec3(0.0f)) return radiance;
  const glm::vec3 hitPosition = w * hit.p0 + u * hit.p1 + v * hit.p2;
  const glm::vec3 shadowOrigin = hitPosition + towardOrigin * in_.epsilon;
  glm::vec3 irradiance(0.0f);
  for (const Light& light : in_.scene.lights) {
    glm::vec3 toLight;
    float distance;
    const float attenuation = lightAttenuation(light, hitPosition, toLight, distance);
    const float nDotL = glm::dot(normal, toLight);
    if (attenuation <= 0.0f || nDotL <= 0.0f) continue;
    const glm::vec3 visibility = lightVisibility(light, shadowOrigin, toLight, distance);
    irradiance += light.color * light.intensity * (attenuation * nDotL * visibility);
  }
  return radiance + diffuse * irradiance;
}

}  // namespace headlight::reference

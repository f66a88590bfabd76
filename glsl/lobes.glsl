// A program built without lobes: the Surface's one unused slot and the
// LOBES_* hook macros with no call, which lobeDefines writes with the calls
// of the variant's lobes otherwise (lib/frame/frame_plan.cpp kHookRows; a
// new hook is a row there and a line here).
#ifndef LOBE_SLOTS
#define LOBE_SLOTS 1
#define LOBES_APPLY(s)
#define LOBES_FRESNEL(s, fresnel)
#define LOBES_SPECULAR_TERM(s, term, alpha, toLight, halfVector, nDotL)
#define LOBES_LAYER_SCALE(s, scale, nDotL)
#define LOBES_LAYER_LIGHT(s, light, nDotL, nDotH)
#define LOBES_ALBEDO_ROUGHNESS(s, roughness)
#define LOBES_SPECULAR_ALBEDO(s, albedo, scaleBias)
#define LOBES_REFLECTION(s, reflected)
#define LOBES_AMBIENT_LAYER(s, ambient, skyVisibility)
#define LOBES_OF_MATERIAL(lobes, normal)
#define LOBES_AT(lobes, pixel)
#define LOBE_TARGET_OUTPUTS
#define LOBES_WRITE_TARGETS(normal)
#endif

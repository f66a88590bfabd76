#pragma once
// The glTF sampler values that TextureRef holds (headlight/scene.hpp). glTF
// defines them as the OpenGL enums of the same names, so they are spelled
// here for code that samples on the CPU without including a GL header.
namespace headlight::reference {

// magFilter / minFilter
constexpr int kGlNearest = 0x2600;  // GL_NEAREST
constexpr int kGlLinear = 0x2601;   // GL_LINEAR

// wrapS / wrapT
constexpr int kGlRepeat = 0x2901;          // GL_REPEAT
constexpr int kGlClampToEdge = 0x812F;     // GL_CLAMP_TO_EDGE
constexpr int kGlMirroredRepeat = 0x8370;  // GL_MIRRORED_REPEAT

}  // namespace headlight::reference

// ---- Textures (docs/textures.md), glTF's convention: (S, T) = (0, 0) is the picture's
// top-left corner, texel (I, J) covers [I, I+1)/W × [J, J+1)/H, wrapping acts on texel
// indices, sRGB is decoded per texel before the bilinear blend. Each image holds the
// texels as facet decoded them (16-bit PPM, a row of zeros on top: POV-Ray's PPM reader
// needs it), read at texel centres without interpolation: the texel's own value.
// glTF's MIRRORED_REPEAT of a texel index: 0 1 … N−1 N−1 … 1 0 0 1 …
#declare Facet_Mirror = function(I, N) {
  select(I - 2*N*floor(I/(2*N)) - N, I - 2*N*floor(I/(2*N)), 2*N - 1 - (I - 2*N*floor(I/(2*N))))
}
// IEC 61966-2-1: C ≤ 0.04045 ? C/12.92 : ((C + 0.055)/1.055)^2.4.
#declare Facet_Srgb = function(C) { select(C - 0.04045, C/12.92, C/12.92, pow((C + 0.055)/1.055, 2.4)) }

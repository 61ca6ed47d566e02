// lit_maps.glsl — the fragment body shared by filament_best.mat and truth.mat: the glTF
// metallic-roughness inputs read from the four maps. The two materials differ only in the
// samplers and roughness map the program binds and in specularAntiAliasing (see the .mat files),
// so that the comparison measures filtering, not a different shading model.
void material(inout MaterialInputs material) {
    vec2 uv = getUV0() * materialParams.uvScale;
    // Tangent space, OpenGL convention (green up), as glTF and footprint's normal maps.
    material.normal = texture(materialParams_normalMap, uv).xyz * 2.0 - 1.0;
    prepareMaterial(material);
    material.baseColor.rgb = materialParams.baseColorFactor * texture(materialParams_baseColorMap, uv).rgb;
    // glTF's metallic factor × its metallic-roughness map's B channel (the program puts it in R).
    material.metallic = materialParams.metallic * texture(materialParams_metallicMap, uv).r;
    // Perceptual roughness (glTF's): the map holds it directly.
    material.roughness = materialParams.roughnessFactor * texture(materialParams_roughnessMap, uv).r;
}

#version 330 core
// bras-kit's lit-mesh shader: pyrender 0.1.45's mesh.frag (shaders/mesh.frag) reduced to what
// bras-kit draws - metallic-roughness materials with no textures, directional lights, no
// shadows - with the same formulas, and each facet lit flat: its normal is the cross product of
// the screen derivatives of the position (primitives carry no normals, so vertices are shared).
#define PI 3.141592653589793
const float min_roughness = 0.04;

struct DirectionalLight {
    vec3 color;
    float intensity;
    vec3 direction;
};

struct Material {
    vec3 emissive_factor;
    vec4 base_color_factor;
    float metallic_factor;
    float roughness_factor;
};

uniform Material material;
uniform DirectionalLight directional_lights[MAX_DIRECTIONAL_LIGHTS];
uniform int n_directional_lights;
uniform vec3 cam_pos;
uniform vec3 ambient_light;

in vec3 frag_position;
out vec4 frag_color;

void main()
{
    float roughness = clamp(material.roughness_factor, min_roughness, 1.0);
    float metallic = clamp(material.metallic_factor, 0.0, 1.0);
    vec4 base_color = material.base_color_factor;
    vec3 c_diff = mix(vec3(0.0), base_color.rgb * (1 - min_roughness), 1.0 - metallic);
    vec3 f0 = mix(vec3(min_roughness), base_color.rgb, metallic);

    vec3 v = normalize(cam_pos - frag_position);  // towards the camera
    vec3 facet = cross(dFdx(frag_position), dFdy(frag_position));
    vec3 n = dot(facet, facet) > 0.0 ? normalize(facet) : v;  // a line has no facet: face the camera

    float nv = clamp(abs(dot(n, v)), 0.001, 1.0);
    float k = (roughness + 1.0) * (roughness + 1.0) / 8.0;  // Smith
    float g1 = nv / (nv * (1.0 - k) + k);
    float a2 = roughness * roughness * roughness * roughness;  // microfacet distribution

    vec3 color = vec3(0.0);
    for (int i = 0; i < n_directional_lights; i++) {
        vec3 l = normalize(-1.0 * directional_lights[i].direction);  // towards the light
        vec3 radiance = directional_lights[i].intensity * directional_lights[i].color;
        vec3 h = normalize(l + v);
        float nl = clamp(dot(n, l), 0.001, 1.0);
        float nh = clamp(dot(n, h), 0.0, 1.0);
        float vh = clamp(dot(v, h), 0.0, 1.0);
        vec3 F = f0 + (1.0 - f0) * pow(clamp(1.0 - vh, 0.0, 1.0), 5.0);  // Fresnel
        float G = g1 * nl / (nl * (1.0 - k) + k);
        float denom = nh * nh * (a2 - 1.0) + 1.0;
        float D = a2 / (PI * denom * denom);
        vec3 diffuse_contrib = (1.0 - F) * c_diff / PI;
        vec3 spec_contrib = F * G * D / (4.0 * nl * nv + 0.001);
        color += nl * radiance * (diffuse_contrib + spec_contrib);
    }
    color += base_color.xyz * ambient_light;
    color += material.emissive_factor * material.emissive_factor;
    frag_color = clamp(vec4(pow(color, vec3(1.0 / 2.2)), base_color.a), 0.0, 1.0);
}

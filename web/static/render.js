// WebGL2 drawing of Folio's mesh with the translucent paper of seed 000 Sec. 4.2
// (eq. 15-17), the same model and constants as the contact sheet of `folio run`
// (cli/src/render/shading.rs and stage.rs): a page reflects diffusely and specularly and
// transmits, so the print on the back of a lifted page shows through, mirrored.
//
//   f   = k_d rho / pi + k_s f_CT + k_t rho rho_back / pi                     (eq. 15)
//   k_t = (1 - F(|n.l|)) e^(-alpha t),  k_d = (1 - F(h.v)) (1 - e^(-alpha t)),  k_s = F(h.v)
//                                                                              (eq. 16, 17)
// with Schlick's F, GGX / Smith f_CT, a directional light of irradiance E, ambient A from
// both sides, and the tone map 1 - e^(-k L) then sRGB. Light from the side seen gives the
// first two terms, light from behind only the third.

const VERTEX = `#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
layout(location = 3) in float a_material;
uniform mat4 u_view_projection;
out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
flat out int v_material;
void main() {
  v_position = a_position;
  v_normal = a_normal;
  v_uv = a_uv;
  v_material = int(a_material + 0.5);
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}`;

const FRAGMENT = `#version 300 es
precision highp float;
precision highp sampler2DArray;
uniform sampler2DArray u_pages;  // 0 active front, 1 active back, 2 left top, 3 right top
uniform vec3 u_eye;
uniform vec3 u_light;            // unit direction to the light
uniform float u_thickness;       // the active page (page units)
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
flat in int v_material;
out vec4 o_color;

const float PI = 3.14159265;
const float IRRADIANCE = 2.6;    // stage.rs CENTRE_IRRADIANCE
const float AMBIENT = 0.15;      // stage.rs AMBIENT
const float EXPOSURE = 1.8;      // stage.rs EXPOSURE
const float ABSORPTION = 200.0;  // shading.rs Paper::default: alpha (1 / page unit)
const float ROUGHNESS = 0.65;
const float F0 = 0.04;
const vec3 PAGE_EDGES = vec3(0.84, 0.82, 0.76);
const vec3 COVER = vec3(0.40, 0.10, 0.08);
const vec3 TABLE = vec3(0.46, 0.38, 0.30);

float schlick(float f0, float c) {
  float m = 1.0 - clamp(c, 0.0, 1.0);
  float m2 = m * m;
  return f0 + (1.0 - f0) * m2 * m2 * m;
}

// GGX distribution with separable Smith masking, without its Fresnel factor.
float cookTorrance(vec3 n, vec3 v, vec3 l) {
  float nl = dot(n, l), nv = dot(n, v);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  vec3 h = normalize(l + v);
  float nh = clamp(dot(n, h), 0.0, 1.0);
  float a = max(ROUGHNESS * ROUGHNESS, 1e-3);
  float a2 = a * a;
  float q = nh * nh * (a2 - 1.0) + 1.0;
  float d = a2 / (PI * q * q);
  float g1l = 2.0 * nl / (nl + sqrt(a2 + (1.0 - a2) * nl * nl));
  float g1v = 2.0 * nv / (nv + sqrt(a2 + (1.0 - a2) * nv * nv));
  return d * g1l * g1v / (4.0 * nl * nv);
}

// Eq. 15-17 plus ambient for a page of transmittance e^(-alpha t); back is the other
// side's albedo at the same point. Transmittance 0 is an opaque paper surface.
vec3 paper(vec3 n, vec3 v, vec3 l, vec3 albedo, vec3 back, float transmitted) {
  float nl = dot(n, l);
  vec3 c = AMBIENT * albedo * ((1.0 - F0) * (1.0 - transmitted) + (1.0 - F0) * transmitted * back);
  if (nl > 0.0) {
    vec3 h = normalize(l + v);
    float f = schlick(F0, dot(h, v));
    float kd = (1.0 - f) * (1.0 - transmitted);
    c += IRRADIANCE * nl * (kd * albedo / PI + f * cookTorrance(n, v, l));
  } else {
    float kt = (1.0 - schlick(F0, -nl)) * transmitted;
    c += IRRADIANCE * (-nl) * kt * albedo * back / PI;
  }
  return c;
}

vec3 lambert(vec3 n, vec3 l, vec3 albedo) {
  return albedo * (IRRADIANCE * max(dot(n, l), 0.0) / PI + AMBIENT);
}

vec3 display(vec3 radiance) {
  vec3 x = clamp(1.0 - exp(-EXPOSURE * max(radiance, vec3(0.0))), 0.0, 1.0);
  return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, x));
}

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(u_eye - v_position);
  vec3 l = u_light;
  vec3 c;
  if (v_material <= 1) {
    // The active page: its own side, and the other side at the same point, mirrored.
    int side = v_material, other = 1 - v_material;
    vec3 albedo = texture(u_pages, vec3(v_uv, float(side))).rgb;
    vec3 back = texture(u_pages, vec3(1.0 - v_uv.x, v_uv.y, float(other))).rgb;
    c = paper(n, v, l, albedo, back, exp(-ABSORPTION * u_thickness));
  } else if (v_material <= 3) {
    // A block's top runs its u from the spine outwards; the left one's page (a verso) is
    // read from its outer edge.
    vec2 uv = v_material == 2 ? vec2(1.0 - v_uv.x, v_uv.y) : v_uv;
    vec3 albedo = texture(u_pages, vec3(uv, float(v_material))).rgb;
    c = paper(n, v, l, albedo, vec3(0.0), 0.0);
  } else if (v_material == 4) {
    c = lambert(n, l, PAGE_EDGES);
  } else if (v_material == 5) {
    c = lambert(n, l, COVER);
  } else {
    c = lambert(n, l, TABLE);
  }
  o_color = vec4(display(c), 1.0);
}`;

// Direction to the light: above, left and in front, as the contact sheet's BOOK_LIGHT.
const LIGHT = (() => {
  const l = [-0.55, 1.0, 0.45];
  const n = Math.hypot(...l);
  return l.map((x) => x / n);
})();

function compile(gl, type, source) {
  const s = gl.createShader(type);
  gl.shaderSource(s, source);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) {
    throw new Error('shader: ' + gl.getShaderInfoLog(s));
  }
  return s;
}

export class Renderer {
  // `gl`: a WebGL2 context; `pageSize`: [width, height] of a page texture in pixels.
  constructor(gl, pageSize) {
    this.gl = gl;
    const p = gl.createProgram();
    gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, VERTEX));
    gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, FRAGMENT));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) {
      throw new Error('program: ' + gl.getProgramInfoLog(p));
    }
    this.program = p;
    this.uniforms = {};
    for (const name of ['u_view_projection', 'u_pages', 'u_eye', 'u_light', 'u_thickness']) {
      this.uniforms[name] = gl.getUniformLocation(p, name);
    }
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    this.buffers = [3, 3, 2, 1].map((size, location) => {
      const b = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.enableVertexAttribArray(location);
      gl.vertexAttribPointer(location, size, gl.FLOAT, false, 0, 0);
      return b;
    });
    this.indexBuffer = gl.createBuffer();
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
    gl.bindVertexArray(null);
    this.indexCount = 0;
    this.texture = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.texture);
    gl.texStorage3D(gl.TEXTURE_2D_ARRAY, 1, gl.SRGB8_ALPHA8, pageSize[0], pageSize[1], 4);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
    gl.texParameteri(gl.TEXTURE_2D_ARRAY, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
  }

  // Uploads a page canvas into texture layer `layer` (0 active front, 1 active back,
  // 2 left top, 3 right top).
  setPage(layer, canvas) {
    const gl = this.gl;
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.texture);
    gl.pixelStorei(gl.UNPACK_FLIP_Y_WEBGL, false);
    gl.texSubImage3D(gl.TEXTURE_2D_ARRAY, 0, 0, 0, layer, canvas.width, canvas.height, 1,
      gl.RGBA, gl.UNSIGNED_BYTE, canvas);
  }

  // Uploads the mesh from views on the module's memory: positions, normals, uvs,
  // materials (Float32Array) and indices (Uint32Array).
  setMesh(positions, normals, uvs, materials, indices) {
    const gl = this.gl;
    gl.bindVertexArray(this.vao);
    [positions, normals, uvs, materials].forEach((data, k) => {
      gl.bindBuffer(gl.ARRAY_BUFFER, this.buffers[k]);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.DYNAMIC_DRAW);
    });
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indexBuffer);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.DYNAMIC_DRAW);
    gl.bindVertexArray(null);
    this.indexCount = indices.length;
  }

  // Draws the mesh seen through `viewProjection` (16 floats) from `eye`; `thickness` is
  // the active page's (one sheet's times the pages held).
  draw(viewProjection, eye, thickness) {
    const gl = this.gl;
    gl.viewport(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight);
    gl.clearColor(0.16, 0.165, 0.19, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.CULL_FACE);
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(this.uniforms.u_view_projection, false, viewProjection);
    gl.uniform3fv(this.uniforms.u_eye, eye);
    gl.uniform3fv(this.uniforms.u_light, LIGHT);
    gl.uniform1f(this.uniforms.u_thickness, thickness);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.texture);
    gl.uniform1i(this.uniforms.u_pages, 0);
    gl.bindVertexArray(this.vao);
    gl.drawElements(gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
  }
}

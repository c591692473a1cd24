// WebGL2 drawing of Folio's mesh with the translucent paper of seed 000 Sec. 4.2
// (eq. 15-17), the same model and constants as the contact sheet of `folio run`
// (cli/src/render/shading.rs and stage.rs): a page reflects diffusely and specularly and
// transmits, so the print on the back of a lifted page shows through, mirrored.
//
//   f   = k_d rho / pi + k_s f_CT + k_t rho rho_back / pi                     (eq. 15)
//   k_t = (1 - F(|n.l|)) e^(-alpha t),  k_d = (1 - F(h.v)) (1 - e^(-alpha t)),  k_s = F(h.v)
//                                                                              (eq. 16, 17)
// with Schlick's F, GGX / Smith f_CT, ambient A from both sides, and the tone map
// 1 - e^(-k L) then sRGB. Light from the side seen gives the first two terms, light from
// behind only the third. The light is the contact sheet's: a point light above, left and
// in front of the book (stage.rs: 1.2 box diagonals from the box's centre along
// BOOK_LIGHT, irradiance E = 2.6 there, falling off as 1/d^2), with its shadow map
// (shadow.rs: depth seen from the light, the lookup moved 2 texels along the normal towards
// the light and one texel plus 1e-3 of the diagonal along the ray, a percentage-closer
// filter over 3 x 3 texels), so a lifted page shadows the page below it and the table.

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
uniform highp sampler2DShadow u_shadow; // depth seen from the light, compared
uniform mat4 u_light_matrix;     // the shadow map's clip matrix
uniform vec3 u_eye;
uniform vec3 u_light;            // the light's position
uniform float u_intensity;       // E d^2: the irradiance at distance d is u_intensity / d^2
uniform vec2 u_shadow_offsets;   // along the normal, along the ray (page units)
uniform float u_thickness;       // the active page (page units)
in vec3 v_position;
in vec3 v_normal;
in vec2 v_uv;
flat in int v_material;
out vec4 o_color;

const float PI = 3.14159265;
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

// Eq. 15-17 plus ambient for a page of transmittance e^(-alpha t) under irradiance e; back
// is the other side's albedo at the same point. Transmittance 0 is an opaque paper surface.
vec3 paper(vec3 n, vec3 v, vec3 l, float e, vec3 albedo, vec3 back, float transmitted) {
  float nl = dot(n, l);
  vec3 c = AMBIENT * albedo * ((1.0 - F0) * (1.0 - transmitted) + (1.0 - F0) * transmitted * back);
  if (nl > 0.0) {
    vec3 h = normalize(l + v);
    float f = schlick(F0, dot(h, v));
    float kd = (1.0 - f) * (1.0 - transmitted);
    c += e * nl * (kd * albedo / PI + f * cookTorrance(n, v, l));
  } else {
    float kt = (1.0 - schlick(F0, -nl)) * transmitted;
    c += e * (-nl) * kt * albedo * back / PI;
  }
  return c;
}

vec3 lambert(vec3 n, vec3 l, float e, vec3 albedo) {
  return albedo * (e * max(dot(n, l), 0.0) / PI + AMBIENT);
}

// The fraction of the light reaching p on a surface of normal n (1 lit, 0 in shadow), as
// shadow.rs's light_at (its 3 x 3 texels filtered by four bilinear depth comparisons);
// points the map does not cover are lit.
float lit(vec3 p, vec3 n) {
  vec3 towards = dot(n, u_light - p) >= 0.0 ? n : -n;
  vec3 q = p + towards * u_shadow_offsets.x + normalize(u_light - p) * u_shadow_offsets.y;
  vec4 c = u_light_matrix * vec4(q, 1.0);
  if (c.w <= 0.0) return 1.0;
  vec3 s = 0.5 * c.xyz / c.w + 0.5;
  if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0)))) return 1.0;
  // Four bilinear comparisons half a texel off the point: a filter over 3 x 3 texels.
  vec2 h = 0.5 / vec2(textureSize(u_shadow, 0));
  return 0.25 * (texture(u_shadow, vec3(s.xy + vec2(-h.x, -h.y), s.z))
    + texture(u_shadow, vec3(s.xy + vec2(h.x, -h.y), s.z))
    + texture(u_shadow, vec3(s.xy + vec2(-h.x, h.y), s.z))
    + texture(u_shadow, vec3(s.xy + vec2(h.x, h.y), s.z)));
}

vec3 display(vec3 radiance) {
  vec3 x = clamp(1.0 - exp(-EXPOSURE * max(radiance, vec3(0.0))), 0.0, 1.0);
  return mix(12.92 * x, 1.055 * pow(x, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, x));
}

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(u_eye - v_position);
  vec3 toLight = u_light - v_position;
  vec3 l = normalize(toLight);
  float e = u_intensity / max(dot(toLight, toLight), 1e-12) * lit(v_position, n);
  vec3 c;
  if (v_material <= 1) {
    // The active page: its own side, and the other side at the same point, mirrored.
    int side = v_material, other = 1 - v_material;
    vec3 albedo = texture(u_pages, vec3(v_uv, float(side))).rgb;
    vec3 back = texture(u_pages, vec3(1.0 - v_uv.x, v_uv.y, float(other))).rgb;
    c = paper(n, v, l, e, albedo, back, exp(-ABSORPTION * u_thickness));
  } else if (v_material <= 3) {
    // A block's top runs its u from the spine outwards; the left one's page (a verso) is
    // read from its outer edge.
    vec2 uv = v_material == 2 ? vec2(1.0 - v_uv.x, v_uv.y) : v_uv;
    vec3 albedo = texture(u_pages, vec3(uv, float(v_material))).rgb;
    c = paper(n, v, l, e, albedo, vec3(0.0), 0.0);
  } else if (v_material == 4) {
    c = lambert(n, l, e, PAGE_EDGES);
  } else if (v_material == 5) {
    c = lambert(n, l, e, COVER);
  } else {
    c = lambert(n, l, e, TABLE);
  }
  o_color = vec4(display(c), 1.0);
}`;

// The shadow pass: depth seen from the light, both faces.
const SHADOW_VERTEX = `#version 300 es
layout(location = 0) in vec3 a_position;
uniform mat4 u_light_matrix;
void main() {
  gl_Position = u_light_matrix * vec4(a_position, 1.0);
}`;

const SHADOW_FRAGMENT = `#version 300 es
precision mediump float;
void main() {}`;

// The light, as the contact sheet's (stage.rs, render.rs): from the box's centre along
// BOOK_LIGHT, LIGHT_DISTANCE box diagonals away, irradiance CENTRE_IRRADIANCE at the centre.
const BOOK_LIGHT = [-0.55, 1.0, 0.45];
const LIGHT_DISTANCE = 1.2;
const CENTRE_IRRADIANCE = 2.6;
// Texels of the shadow map on a side (stage.rs SHADOW_RESOLUTION).
const SHADOW_RESOLUTION = 1024;

const sub = (a, b) => a.map((x, k) => x - b[k]);
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
  a[0] * b[1] - a[1] * b[0]];
const normalize = (v) => { const n = Math.hypot(...v); return v.map((x) => x / n); };

// Column-major 4 x 4 matrices (WebGL's layout).
function lookAt(eye, target) {
  const f = normalize(sub(target, eye));
  const up = Math.abs(f[1]) > 0.99 ? [0, 0, 1] : [0, 1, 0];
  const s = normalize(cross(f, up));
  const u = cross(s, f);
  return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
    -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
}

function perspective(tanHalf, near, far) {
  const f = 1 / tanHalf;
  return [f, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1,
    0, 0, (2 * far * near) / (near - far), 0];
}

function multiply(a, b) {
  const c = new Array(16).fill(0);
  for (let col = 0; col < 4; col++) {
    for (let row = 0; row < 4; row++) {
      for (let k = 0; k < 4; k++) c[col * 4 + row] += a[k * 4 + row] * b[col * 4 + k];
    }
  }
  return c;
}

function transform(m, p) {
  return [0, 1, 2].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
}

// The light and its shadow map's camera for the box [lo, hi] (page units): a perspective
// from the light through the box's corners and the table's points where the shadows of the
// box's top corners fall (the table is the box's bottom plane).
export function stageLight(lo, hi) {
  const centre = lo.map((x, k) => 0.5 * (x + hi[k]));
  const diagonal = Math.hypot(...sub(hi, lo));
  const distance = LIGHT_DISTANCE * diagonal;
  const direction = normalize(BOOK_LIGHT);
  const light = centre.map((x, k) => x + distance * direction[k]);
  const view = lookAt(light, centre);
  const corners = [];
  for (const x of [lo[0], hi[0]]) {
    for (const z of [lo[2], hi[2]]) {
      corners.push([x, lo[1], z], [x, hi[1], z]);
      // The top corner's shadow on the table: from the light through the corner (the
      // light is above the box: BOOK_LIGHT rises at 55 degrees, 1.2 diagonals away).
      if (light[1] > hi[1]) {
        const t = (light[1] - lo[1]) / (light[1] - hi[1]);
        corners.push([light[0] + (x - light[0]) * t, lo[1], light[2] + (z - light[2]) * t]);
      }
    }
  }
  let tanHalf = 1e-3, near = Infinity, far = 0;
  for (const p of corners) {
    const v = transform(view, p);
    const depth = -v[2];
    tanHalf = Math.max(tanHalf, Math.abs(v[0]) / depth, Math.abs(v[1]) / depth);
    near = Math.min(near, depth);
    far = Math.max(far, depth);
  }
  tanHalf *= 1.02;
  const matrix = multiply(perspective(tanHalf, 0.9 * near, 1.1 * far), view);
  // One texel at the centre's distance; the offsets of shadow.rs.
  const texel = (2 * distance * tanHalf) / SHADOW_RESOLUTION;
  return {
    light,
    intensity: CENTRE_IRRADIANCE * distance * distance,
    matrix: new Float32Array(matrix),
    offsets: [2 * texel, texel + 1e-3 * diagonal],
  };
}

function link(gl, vertex, fragment) {
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, vertex));
  gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, fragment));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) {
    throw new Error('program: ' + gl.getProgramInfoLog(p));
  }
  return p;
}

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
    this.program = link(gl, VERTEX, FRAGMENT);
    this.uniforms = {};
    for (const name of ['u_view_projection', 'u_pages', 'u_shadow', 'u_light_matrix', 'u_eye',
      'u_light', 'u_intensity', 'u_shadow_offsets', 'u_thickness']) {
      this.uniforms[name] = gl.getUniformLocation(this.program, name);
    }
    this.shadowProgram = link(gl, SHADOW_VERTEX, SHADOW_FRAGMENT);
    this.shadowMatrix = gl.getUniformLocation(this.shadowProgram, 'u_light_matrix');
    this.shadowMap = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this.shadowMap);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.DEPTH_COMPONENT24, SHADOW_RESOLUTION,
      SHADOW_RESOLUTION);
    for (const [key, value] of [[gl.TEXTURE_MIN_FILTER, gl.LINEAR],
      [gl.TEXTURE_MAG_FILTER, gl.LINEAR], [gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE],
      [gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE],
      [gl.TEXTURE_COMPARE_MODE, gl.COMPARE_REF_TO_TEXTURE],
      [gl.TEXTURE_COMPARE_FUNC, gl.LEQUAL]]) {
      gl.texParameteri(gl.TEXTURE_2D, key, value);
    }
    this.shadowTarget = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.shadowTarget);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D,
      this.shadowMap, 0);
    gl.drawBuffers([gl.NONE]);
    gl.readBuffer(gl.NONE);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE) {
      throw new Error('the shadow map cannot be drawn into');
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    this.stage = stageLight([-1, -1, -1], [1, 1, 1]);
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

  // The box the view frames (6 numbers: min corner, max corner; Folio.stage()): places the
  // light and frames its shadow map.
  setStage(box) {
    this.stage = stageLight([box[0], box[1], box[2]], [box[3], box[4], box[5]]);
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
    const stage = this.stage;
    // The shadow map: every face, nearest depth from the light.
    gl.bindFramebuffer(gl.FRAMEBUFFER, this.shadowTarget);
    gl.viewport(0, 0, SHADOW_RESOLUTION, SHADOW_RESOLUTION);
    gl.clear(gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.disable(gl.CULL_FACE);
    gl.useProgram(this.shadowProgram);
    gl.uniformMatrix4fv(this.shadowMatrix, false, stage.matrix);
    gl.bindVertexArray(this.vao);
    gl.drawElements(gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight);
    gl.clearColor(0.16, 0.165, 0.19, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.CULL_FACE);
    gl.useProgram(this.program);
    gl.uniformMatrix4fv(this.uniforms.u_view_projection, false, viewProjection);
    gl.uniform3fv(this.uniforms.u_eye, eye);
    gl.uniform3fv(this.uniforms.u_light, stage.light);
    gl.uniform1f(this.uniforms.u_intensity, stage.intensity);
    gl.uniformMatrix4fv(this.uniforms.u_light_matrix, false, stage.matrix);
    gl.uniform2fv(this.uniforms.u_shadow_offsets, stage.offsets);
    gl.uniform1f(this.uniforms.u_thickness, thickness);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D_ARRAY, this.texture);
    gl.uniform1i(this.uniforms.u_pages, 0);
    gl.activeTexture(gl.TEXTURE1);
    gl.bindTexture(gl.TEXTURE_2D, this.shadowMap);
    gl.uniform1i(this.uniforms.u_shadow, 1);
    gl.bindVertexArray(this.vao);
    gl.drawElements(gl.TRIANGLES, this.indexCount, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
  }
}

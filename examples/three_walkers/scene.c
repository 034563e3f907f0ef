#include "scene.h"

#include <GLES3/gl3.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const char* kVs =
    "#version 300 es\n"
    "layout(location = 0) in vec3 a_position;\n"
    "uniform mat4 u_mvp;\n"
    "void main() { gl_Position = u_mvp * vec4(a_position, 1.0); }\n";
static const char* kFs =
    "#version 300 es\n"
    "precision mediump float;\n"
    "uniform vec4 u_colour;\n"
    "layout(location = 0) out vec4 o;\n"
    "void main() { o = u_colour; }\n";

/* Ground: a 8 x 8 square at y = 0; box: 0.6 wide, 0.8 high, in front of the right walker. */
static const float kGround[] = {-4, 0, -4, 4, 0, -4, 4, 0, 4, -4, 0, -4, 4, 0, 4, -4, 0, 4};
#define BOX_X0 0.85f
#define BOX_X1 1.55f
#define BOX_Z0 0.6f
#define BOX_Z1 1.2f
#define BOX_H 0.8f

static int box_face(float* v, const float a[3], const float b[3], const float c[3],
                    const float d[3]) {
    const float* q[6] = {a, b, c, a, c, d};
    for (int i = 0; i < 6; ++i) memcpy(v + 3 * i, q[i], 3 * sizeof(float));
    return 18;
}

static int box_vertices(float* v) {
    const float p[8][3] = {{BOX_X0, 0, BOX_Z0},     {BOX_X1, 0, BOX_Z0},    {BOX_X1, BOX_H, BOX_Z0},
                           {BOX_X0, BOX_H, BOX_Z0}, {BOX_X0, 0, BOX_Z1},    {BOX_X1, 0, BOX_Z1},
                           {BOX_X1, BOX_H, BOX_Z1}, {BOX_X0, BOX_H, BOX_Z1}};
    int n = 0;
    n += box_face(v + n, p[4], p[5], p[6], p[7]); /* front (+z, toward the camera) */
    n += box_face(v + n, p[1], p[0], p[3], p[2]); /* back */
    n += box_face(v + n, p[0], p[4], p[7], p[3]); /* left */
    n += box_face(v + n, p[5], p[1], p[2], p[6]); /* right */
    n += box_face(v + n, p[3], p[7], p[6], p[2]); /* top */
    return n / 3;
}

static unsigned compile(unsigned type, const char* src) {
    unsigned s = glCreateShader(type);
    glShaderSource(s, 1, &src, NULL);
    glCompileShader(s);
    return s;
}

int scene_init(scene* s) {
    float v[18 + 5 * 18];
    memcpy(v, kGround, sizeof(kGround));
    s->vertex_count = 6 + box_vertices(v + 18);
    s->program = glCreateProgram();
    glAttachShader(s->program, compile(GL_VERTEX_SHADER, kVs));
    glAttachShader(s->program, compile(GL_FRAGMENT_SHADER, kFs));
    glLinkProgram(s->program);
    GLint ok = 0;
    glGetProgramiv(s->program, GL_LINK_STATUS, &ok);
    if (!ok) return -1;
    s->colour_location = glGetUniformLocation(s->program, "u_colour");
    s->mvp_location = glGetUniformLocation(s->program, "u_mvp");
    glGenVertexArrays(1, &s->vao);
    glBindVertexArray(s->vao);
    glGenBuffers(1, &s->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, s->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(s->vertex_count * 3 * sizeof(float)), v,
                 GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, NULL);
    return 0;
}

void scene_draw(const scene* s, const float view_projection[16]) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glUseProgram(s->program);
    glUniformMatrix4fv(s->mvp_location, 1, GL_FALSE, view_projection);
    glBindVertexArray(s->vao);
    glUniform4f(s->colour_location, 0.55f, 0.55f, 0.55f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glUniform4f(s->colour_location, 0.2f, 0.35f, 0.8f, 1.0f);
    glDrawArrays(GL_TRIANGLES, 6, s->vertex_count - 6);
}

void scene_destroy(scene* s) {
    glDeleteBuffers(1, &s->vbo);
    glDeleteVertexArrays(1, &s->vao);
    glDeleteProgram(s->program);
}

void mat4_multiply(float out[16], const float a[16], const float b[16]) {
    float r[16];
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            float sum = 0;
            for (int k = 0; k < 4; ++k) sum += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = sum;
        }
    memcpy(out, r, sizeof(r));
}

void mat4_translate(float out[16], float x, float y, float z) {
    memset(out, 0, 16 * sizeof(float));
    out[0] = out[5] = out[10] = out[15] = 1.0f;
    out[12] = x;
    out[13] = y;
    out[14] = z;
}

void mat4_perspective(float out[16], float fovy, float aspect, float near, float far) {
    const float f = 1.0f / tanf(0.5f * fovy);
    memset(out, 0, 16 * sizeof(float));
    out[0] = f / aspect;
    out[5] = f;
    out[10] = (far + near) / (near - far);
    out[11] = -1.0f;
    out[14] = 2.0f * far * near / (near - far);
}

static void normalise(float v[3]) {
    const float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    v[0] /= l, v[1] /= l, v[2] /= l;
}

void mat4_look_at(float out[16], const float eye[3], const float target[3]) {
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    normalise(f);
    float s[3] = {f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0}; /* f x up */
    normalise(s);
    const float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2],
                        s[0] * f[1] - s[1] * f[0]};
    const float m[16] = {s[0],
                         u[0],
                         -f[0],
                         0,
                         s[1],
                         u[1],
                         -f[1],
                         0,
                         s[2],
                         u[2],
                         -f[2],
                         0,
                         -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                         -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                         f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2],
                         1};
    memcpy(out, m, sizeof(m));
}

int write_ppm(const char* path, int width, int height, const unsigned char* rgba) {
    FILE* f = fopen(path, "wb");
    if (!f) return -1;
    fprintf(f, "P6\n%d %d\n255\n", width, height);
    for (int y = height - 1; y >= 0; --y)
        for (int x = 0; x < width; ++x) fwrite(rgba + ((size_t)y * width + x) * 4, 1, 3, f);
    return fclose(f) == 0 ? 0 : -1;
}

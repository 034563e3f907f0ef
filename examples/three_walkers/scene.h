/* The application's own part of the frame: a ground plane and a box with its own shader,
 * camera matrices, and writing the frame to a PPM file. Nothing here knows about stipple. */
#ifndef SCENE_H
#define SCENE_H

typedef struct scene {
    unsigned program, vao, vbo;
    int colour_location, mvp_location, vertex_count;
} scene;

int scene_init(scene* s); /* 0 on success */
/* Draws the ground (grey) and the box (blue) with depth writes on. */
void scene_draw(const scene* s, const float view_projection[16]);
void scene_destroy(scene* s);

/* Column-major 4x4 matrices (the GL / stipple_app_view layout). */
void mat4_look_at(float out[16], const float eye[3], const float target[3]);
void mat4_perspective(float out[16], float fovy_radians, float aspect, float near, float far);
void mat4_translate(float out[16], float x, float y, float z);
void mat4_multiply(float out[16], const float a[16], const float b[16]);

/* Writes RGBA8 pixels, bottom row first (GL order), as a binary PPM; 0 on success. */
int write_ppm(const char* path, int width, int height, const unsigned char* rgba);

#endif

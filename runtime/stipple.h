/* stipple C API: load a .stip asset and draw animated stipple frames with GLES 3.
 *
 * The caller owns the GL context (make it current before any player call) and passes its
 * get-proc-address; the player draws into its own offscreen framebuffer and hands frames
 * back as RGBA8. Descriptions are zero-initialised structs: zero means "default" (sokol
 * style); stipple_player_desc_resolve shows what a description resolves to. No call throws;
 * failures return a stipple_result and stipple_last_error() says what went wrong in one
 * line. All memory is taken in the create/load calls; drawing a frame allocates nothing.
 *
 *   stipple_asset* asset;
 *   if (stipple_asset_load_file("man.stip", &asset) != STIPPLE_OK) puts(stipple_last_error());
 *   stipple_player_desc desc = {0};
 *   desc.get_proc_address = (stipple_get_proc_fn)eglGetProcAddress;
 *   stipple_player* player;
 *   stipple_player_create(asset, &desc, &player);
 *   stipple_player_draw(player, 0, t);
 *   stipple_player_read_rgba(player, pixels);
 */
#ifndef STIPPLE_H
#define STIPPLE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum stipple_result {
    STIPPLE_OK = 0,
    STIPPLE_ERROR_INVALID_ARGUMENT,
    STIPPLE_ERROR_IO,
    STIPPLE_ERROR_BAD_ASSET, /* truncated, corrupted or inconsistent asset */
    STIPPLE_ERROR_UNSUPPORTED_VERSION,
    STIPPLE_ERROR_GL, /* missing GL entry point, shader or framebuffer error */
    STIPPLE_ERROR_OUT_OF_MEMORY
} stipple_result;

typedef struct stipple_asset stipple_asset;
typedef struct stipple_player stipple_player;

/* Paintstroke breadthwise quality (GI'98 §4.3). AUTO (0, the default) picks 0, 1 or 2 per
 * stroke by its projected radius. */
typedef enum stipple_stroke_quality {
    STIPPLE_STROKE_QUALITY_AUTO = 0,
    STIPPLE_STROKE_QUALITY_0 = 1, /* one polygon per segment facing the viewer */
    STIPPLE_STROKE_QUALITY_1 = 2, /* two per side */
    STIPPLE_STROKE_QUALITY_2 = 3  /* four per side */
} stipple_stroke_quality;
typedef void* (*stipple_get_proc_fn)(const char* name);

/* stipple_player_desc.path */
enum { STIPPLE_PATH_CPU = 0, STIPPLE_PATH_GPU = 1 };

/* Looks (docs/styles.md): the same names as stipple-play --style (stipple_style_name). */
typedef enum stipple_style {
    STIPPLE_STYLE_CLASSIC = 0, /* black dots over white paper (thesis §3.2) */
    STIPPLE_STYLE_TOON,        /* banded fill in the part/fill colour, darker dots (§7.2) */
    STIPPLE_STYLE_COLOUR,      /* dots in the surface colour over the paper (§8.6) */
    STIPPLE_STYLE_TRANSPARENT  /* transparent parts draw only dots and lines (§7.4) */
} stipple_style;
/* "classic", "toon", "colour", "transparent"; NULL outside the enum. */
const char* stipple_style_name(int style);
/* The stipple_style named `name`, or -1. */
int stipple_find_style(const char* name);

/* Defaults and limits come from one table (runtime/frame_config.h, kFrameSettings); a value
 * outside its range makes stipple_player_create and stipple_player_desc_resolve return
 * STIPPLE_ERROR_INVALID_ARGUMENT. */
typedef struct stipple_player_desc {
    int width, height;            /* offscreen image size in [16, 16384]; 0: 640 x 480 */
    float zoom;                   /* in [0.01, 1000]; 0: 1 (rest-pose bounds fit the view) */
    float yaw_degrees;            /* camera orbit around the vertical axis, in [-3600, 3600] */
    float pitch_degrees;          /* camera elevation in [-90, 90] (90: looking straight down) */
    int use_constant_tone;        /* 0: Lambert lighting; 1: constant_tone everywhere */
    float constant_tone;          /* target tone in [0, 1] when use_constant_tone */
    float max_point_size;         /* stipple diameter in pixels, in [0.5, 32]; 0: 3 */
    int no_relevance_update;      /* 1: keep rest-pose relevance (thesis Alg. 6.3 only) */
    int no_silhouettes;           /* 1: no silhouette lines */
    int dual_quaternion_skinning; /* 1: DQS instead of linear blend skinning */
    int dark_tone_set;            /* 1: use dark_tone; 0: 0.6 */
    float dark_tone;              /* darkest tone lighting asks for, in [0, 1] (thesis §8.4) */
    int refinement_budget;        /* extra points per frame where the baked hierarchy runs out
                                     (close-ups, stretch), at most 4194304; 0: 262144, < 0: none.
                                     Memory for them is taken at create: about 72 bytes per
                                     point. */
    uint32_t background_rgb;      /* 0xRRGGBB; used only when background_set */
    int background_set;           /* 0: white paper (0xFFFFFF) */
    int check_gl_errors;          /* 1: call glGetError after each pass (depth, lines, dots) and
                                     each readback; stipple_player_gl_errors counts what it
                                     reports. A debug aid: each check is a driver round trip */
    int no_strokes;               /* 1: do not draw the asset's paintstrokes (STRK section) */
    int stroke_quality;           /* stipple_stroke_quality; 0: auto */
    float stroke_tol_theta;       /* GI'98 tol_theta in pixels, in [0.05, 64]; 0: 1 */
    float stroke_tol_z;           /* GI'98 tol_z in pixels, in [0.05, 64]; 0: 0.5 */
    float stroke_lod_px;          /* draw a stroke where its root point's relevance radius
                                     projects to >= this many pixels, in [0, 256]; 0: all */
    float stroke_nudge;           /* GI'98 §4.4: how far quality-0 edge normals lean toward the
                                     centre normal, in (0, 1]; 0: 0.5, < 0: no nudge */
    int stroke_vertex_budget;     /* tessellated vertices per frame, in [1024, 8388608]; 0:
                                     262144 (48 bytes each, taken only if the asset has
                                     strokes) */
    int path;                     /* where place, relevance and size run: 0 (STIPPLE_PATH_CPU,
                                     the default) or 1 (STIPPLE_PATH_GPU: a GLES 3 vertex shader
                                     with transform feedback, docs/gpu-path.md) */
    int path_reserved;            /* 0 (keeps the struct free of padding) */
    int style;                    /* stipple_style (docs/styles.md); 0: STIPPLE_STYLE_CLASSIC;
                                     or a particle style (stipple_find_style("ink"),
                                     stipple_register_style; docs/particles.md) */
    int toon_bands;               /* toon ramp bands, 2 or 3; 0: 3 */
    uint32_t fill_rgb;            /* 0xRRGGBB: toon fill, colour dots without LOOK colours;
                                     used only when fill_set */
    int fill_set;                 /* 0: 0x8CCC59 */
    float toon_ink;               /* toon dots: fill colour times this, in (0, 1]; 0: 0.4,
                                     < 0: black */
    float tone_gamma;             /* tone curve T -> T^gamma before the size rule, in [0.1, 10]
                                     (> 1 lighter); 0: 1 */
    float tone_contrast;          /* then 0.5 + (T - 0.5) contrast, in [0.1, 10]; 0: 1 */
    int no_creases;               /* 1: no crease lines (the asset's LOOK, thesis §8.2) */
    int no_lod;                   /* 1: run place, relevance and size on every point; 0: only on
                                     the point clusters in view and front-facing, cut where no
                                     dot can draw (same dots, docs/lod.md) */
    int threads;                  /* threads for place, relevance and size over point ranges
                                     (byte-identical output); 0: 1, -1: the hardware's (at
                                     most 8), else 1..64 */
    /* Memory: everything a player takes, taken at create. Either an allocator hook (allocate
     * and release with allocator_user; allocate returns 16-byte aligned memory or NULL), or
     * one block (memory, memory_size) of at least stipple_player_memory_bytes() bytes, 16-byte
     * aligned, which must outlive the player; or neither: operator new. */
    void* (*allocate)(size_t bytes, void* user);
    void (*release)(void* pointer, void* user);
    void* allocator_user;
    void* memory;
    size_t memory_size;
    stipple_get_proc_fn get_proc_address; /* required */
} stipple_player_desc;

/* One line describing the last failure on this thread ("" if none). */
const char* stipple_last_error(void);

/* Which check of the last failed asset load on this thread failed (the C++ loader's
 * stipple::LoadError, docs/errors.md): 0 none, then in this order. */
typedef enum stipple_load_error {
    STIPPLE_LOAD_OK = 0,
    STIPPLE_LOAD_IO_ERROR,
    STIPPLE_LOAD_BAD_MAGIC,
    STIPPLE_LOAD_UNSUPPORTED_VERSION,
    STIPPLE_LOAD_WRONG_ENDIANNESS,
    STIPPLE_LOAD_TRUNCATED,
    STIPPLE_LOAD_CHECKSUM_MISMATCH,
    STIPPLE_LOAD_MISSING_SECTION,
    STIPPLE_LOAD_MALFORMED_SECTION,
    STIPPLE_LOAD_OUT_OF_RANGE,
    STIPPLE_LOAD_BAD_VALUE,
    STIPPLE_LOAD_OUT_OF_MEMORY,
    STIPPLE_LOAD_INVALID_ARGUMENT,
    STIPPLE_LOAD_COUNT_OVER_LIMIT,
    STIPPLE_LOAD_COUNT_EXCEEDS_DATA,
    STIPPLE_LOAD_DECODED_SIZE_LIMIT,
    STIPPLE_LOAD_ZERO_COUNT,
    STIPPLE_LOAD_BAD_NORMAL,
    STIPPLE_LOAD_BAD_SKIN_WEIGHT,
    STIPPLE_LOAD_BAD_RADIUS
} stipple_load_error;
stipple_load_error stipple_last_load_error(void);

/* A logger in place of silence: every failure's one-line message (level 2, the same text as
 * stipple_last_error) and warnings (level 1: a GL error seen by check_gl_errors, strokes left
 * out by a full stroke budget) go to `fn` with `user`, on the calling thread. NULL fn: no
 * logging (the default; the library never writes to stdout or stderr). Not thread-safe to
 * change while other threads call the library. */
typedef void (*stipple_log_fn)(int level, const char* message, void* user);
void stipple_set_logger(stipple_log_fn fn, void* user);

/* Loading validates every byte before use and fails with STIPPLE_ERROR_BAD_ASSET, naming the
 * check in stipple_last_error() (docs/errors.md lists them all), on a truncated, corrupted or
 * hostile asset. NULL path, data or out, or size 0: STIPPLE_ERROR_INVALID_ARGUMENT. */
stipple_result stipple_asset_load_file(const char* path, stipple_asset** out);
stipple_result stipple_asset_load_memory(const void* data, size_t size, stipple_asset** out);

/* Load settings; zero-initialise, zero means default. */
typedef struct stipple_load_desc {
    /* Memory the load may take beyond the file's own copy for decoded sections (clip key
     * values, point arrays). An asset that would need more fails with
     * STIPPLE_ERROR_BAD_ASSET before the memory is taken. 0: 16 times the file size plus
     * 1 MiB (bundled assets need at most about 4 times; see docs/errors.md). */
    uint64_t max_decoded_bytes;
} stipple_load_desc;

/* As stipple_asset_load_file / _memory, with load settings; desc may be NULL (defaults). */
stipple_result stipple_asset_load_file_ex(const char* path, const stipple_load_desc* desc,
                                          stipple_asset** out);
stipple_result stipple_asset_load_memory_ex(const void* data, size_t size,
                                            const stipple_load_desc* desc, stipple_asset** out);
void stipple_asset_destroy(stipple_asset* asset);
uint32_t stipple_asset_point_count(const stipple_asset* asset);
uint32_t stipple_asset_clip_count(const stipple_asset* asset);
uint32_t stipple_asset_stroke_count(const stipple_asset* asset);                /* 0 without STRK */
const char* stipple_asset_clip_name(const stipple_asset* asset, uint32_t clip); /* NULL if none */
float stipple_asset_clip_duration(const stipple_asset* asset, uint32_t clip);
int stipple_asset_find_clip(const stipple_asset* asset, const char* name_or_index); /* -1 */

/* Writes `in` with every default filled in and every field explicit (dark_tone_set and
 * background_set 1, refinement_budget -1 for none, constant_tone 0 without
 * use_constant_tone) to `out`; get_proc_address is copied. STIPPLE_ERROR_INVALID_ARGUMENT if
 * a value is outside its range. `out` may be `in`. */
stipple_result stipple_player_desc_resolve(const stipple_player_desc* in, stipple_player_desc* out);

/* The bytes stipple_player_create takes for `asset` with `desc` (its allocator or block must
 * provide them); players over one asset share the asset's memory. 0 if desc is invalid. */
size_t stipple_player_memory_bytes(const stipple_asset* asset, const stipple_player_desc* desc);

/* The asset must outlive the player. Fails with STIPPLE_ERROR_INVALID_ARGUMENT (a setting out
 * of range, no get_proc_address), STIPPLE_ERROR_GL or STIPPLE_ERROR_OUT_OF_MEMORY. */
stipple_result stipple_player_create(const stipple_asset* asset, const stipple_player_desc* desc,
                                     stipple_player** out);
/* Poses clip `clip` (-1 or no such clip: the rest pose) at `time_seconds` and draws into the
 * player's own offscreen image (stipple_player_read_rgba), with the orbit camera of the desc
 * or the camera of the last stipple_player_draw_into. Clips loop: the time is wrapped into
 * [0, duration). Leaves GL state as its passes set it (create does one such draw too):
 * applications sharing the context use stipple_player_draw_into, which restores it. */
void stipple_player_draw(stipple_player* player, int clip, float time_seconds);
/* Layers clip `clip2` at `time2` over `clip` at `time` with weight `weight2`, clamped to
 * [0, 1] (0: only `clip`; ramp it from 0 to 1 for a crossfade; clip2 -1: no layer) and draws.
 * Both clips loop. */
void stipple_player_draw_blend(stipple_player* player, int clip, float time, int clip2, float time2,
                               float weight2);
/* Drawing into the application's own frame (runtime/app_frame.h): its camera, framebuffer
 * and depth. Matrices are column-major float[16] (GL / GLM layout). */
typedef struct stipple_app_view {
    float view[16];       /* world to eye space */
    float projection[16]; /* eye to clip space (perspective, GL conventions) */
    float model[16];      /* the asset's space to world space */
    int viewport[4];      /* x, y, width, height in pixels (width and height in [1, 16384]) */
    int framebuffer_set;  /* 0: draw into the framebuffer bound for drawing at the call; */
    unsigned framebuffer; /* 1: into this GL framebuffer (0: the default one); restored after */
} stipple_app_view;

/* Poses `clip` at `time_seconds` (layered with clip2 at time2 by weight2 as in
 * stipple_player_draw_blend; clip2 -1: none) for the application's camera and draws into the
 * framebuffer bound for drawing, depth-tested against the depth it holds: the body in the
 * paper colour (writing depth), strokes, silhouettes and dots. The application's GL state
 * (program, vertex array, array buffer, framebuffers, viewport, blending, depth and colour
 * settings, culling, line width, texture unit 0) is restored before it returns. For exact
 * dot visibility create the player with the viewport's width and height. NULL player or
 * view, or a viewport out of range: nothing is drawn and stipple_last_error says why. */
void stipple_player_draw_into(stipple_player* player, const stipple_app_view* view, int clip,
                              float time, int clip2, float time2, float weight2);

/* The orbit camera the player uses (zoom, yaw, pitch, field of view of `desc`, framing the
 * asset): view and projection matrices for stipple_app_view, so an application can start
 * from the player's framing. */
stipple_result stipple_orbit_camera(const stipple_asset* asset, const stipple_player_desc* desc,
                                    float view[16], float projection[16]);

/* Settings that change between frames without re-creating the player (each is resolved like
 * the desc: STIPPLE_ERROR_INVALID_ARGUMENT naming the value out of range, and then nothing
 * changes). */
typedef struct stipple_light {
    float direction[3]; /* toward the light; any non-zero length */
    float intensity;    /* in [0, 16] */
    int world_space;    /* 0: camera space (turns with the camera), 1: world space */
} stipple_light;
/* Up to 4 directional lights plus ambient in [0, 1]; a point's lighting is ambient + the sum of
 * intensity * max(N.L, 0), clamped to 1, and its tone runs from dark_tone (unlit) to white.
 * count 0: ambient alone. The default: one camera-space key light from the upper left. */
stipple_result stipple_player_set_lights(stipple_player* player, const stipple_light* lights,
                                         int count, float ambient);
/* Colours as 0xRRGGBB: the body (paper), dots and silhouettes (ink), the player's own image's
 * background. */
stipple_result stipple_player_set_colours(stipple_player* player, uint32_t paper_rgb,
                                          uint32_t ink_rgb, uint32_t background_rgb);
/* Silhouette lines on or off, and their width in pixels ([0.5, 16]; 0 keeps the width). */
stipple_result stipple_player_set_silhouettes(stipple_player* player, int on, float width);
/* Tone: lighting (use_constant_tone 0) or a constant tone in [0, 1]; the largest dot in
 * pixels ([0.5, 32]; 0 keeps it). */
stipple_result stipple_player_set_tone(stipple_player* player, int use_constant_tone, float tone,
                                       float max_point_size);

/* The look between frames: style (stipple_style), the tone curve (gamma, contrast in [0.1, 10];
 * 1, 1: none) and crease lines on or off. */
stipple_result stipple_player_set_style(stipple_player* player, int style, float tone_gamma,
                                        float tone_contrast, int creases);

/* width * height * 4 bytes, bottom row first (GL order). */
void stipple_player_read_rgba(stipple_player* player, uint8_t* rgba);
uint32_t stipple_player_points_drawn(const stipple_player* player);
/* Paintstrokes the last frame drew and the triangles they were tessellated into. */
uint32_t stipple_player_strokes_drawn(const stipple_player* player);
uint32_t stipple_player_stroke_triangles(const stipple_player* player);
/* GL errors reported since create when desc.check_gl_errors is 1 (always 0 otherwise). Any
 * non-zero count is a bug in the player or a broken context; stipple-play --check-gl names
 * the pass of the first one. */
uint32_t stipple_player_gl_errors(const stipple_player* player);
void stipple_player_destroy(stipple_player* player);

/* ---- View-dependent particles (GI'01; docs/particles.md) ----------------------------------
 * Besides the stipple looks, stipple_player_desc.style may name a particle style: strokes at
 * the particles of the point hierarchy, folded and unfolded every frame to hold a density on
 * screen. The built-in ones follow the paper: "painterly-long", "painterly-dab", "sketch",
 * "cartoon", "graftals", "charcoal", "two-tone", "ink" (stipple_find_style gives their
 * numbers). A user style starts from a built-in one and may replace two of its stages with
 * callbacks; it is registered once, before creating the players that use it. */

/* One frame's particles as the callbacks see them, structure of arrays (count entries each). */
typedef struct stipple_particles {
    uint32_t count;
    const uint32_t* id; /* the particle: a point of the hierarchy, coarse first */
    const float* x;     /* pixels, origin top-left */
    const float* y;
    const float* depth;          /* window depth in [0, 1]; > 1: behind the camera */
    const float* radius_px;      /* relevance radius on screen; children are half this apart */
    const float* intensity;      /* lighting in [0, 1] */
    const float* facing;         /* N.V: 1 facing the viewer, 0 on the silhouette, < 0 away */
    const float* angle;          /* the style's orientation field on screen, radians */
    const float* foreshortening; /* 1: the field lies in the image plane, 0: points at the eye */
    const float* alpha;          /* fade in [0, 1] (stage 1's joins and folds, back faces) */
    const uint8_t* unfolded;     /* adjust only: 1 if the particle is unfolded now */
} stipple_particles;

/* Brushes of a stroke (generated by code: docs/particles.md). */
enum {
    STIPPLE_BRUSH_LONG_THIN = 0,
    STIPPLE_BRUSH_ROUND_DAB = 1,
    STIPPLE_BRUSH_CRAYON = 2,
    STIPPLE_BRUSH_GRAFTAL = 3,
    STIPPLE_BRUSH_SOLID = 4
};

/* One stroke: a quad of length x width pixels at (x, y), turned by angle, textured with the
 * brush, in colour (fill: a graftal's inside), drawn whole if its centre passes the depth test. */
typedef struct stipple_stroke {
    float x, y, depth, angle; /* pixels (origin top-left), window depth, radians */
    float length, width;      /* pixels */
    float brush;              /* STIPPLE_BRUSH_* */
    float alpha;              /* opacity in [0, 1] */
    uint8_t rgba[4];          /* colour (alpha unused) */
    uint8_t fill[4];          /* graftal fill (alpha unused) */
} stipple_stroke;

/* Stage 1: write unfold[k] = 1 to show particle k's children this frame, 0 to fold them. */
typedef void (*stipple_adjust_fn)(const stipple_particles* particles, uint8_t* unfold, void* user);
/* Stage 4: write at most `capacity` strokes and the id of each one's particle; return the
 * count. */
typedef uint32_t (*stipple_strokes_fn)(const stipple_particles* particles, stipple_stroke* out,
                                       uint32_t* out_id, uint32_t capacity, void* user);

typedef struct stipple_style_desc {
    const char* name;           /* 1-31 characters of [a-z0-9_-], not taken */
    const char* base;           /* the built-in style it starts from; NULL: "painterly-long" */
    stipple_adjust_fn adjust;   /* NULL: the base's criterion (density, silhouettes) */
    stipple_strokes_fn strokes; /* NULL: the base's strokes */
    void* user;                 /* passed to both */
    float spacing_px;           /* stage 1's density target in pixels; 0: the base's */
    int fade_frames;            /* frames a fade takes, in [1, 255]; 0: the base's */
} stipple_style_desc;

/* Registers a particle style; returns its style number for stipple_player_desc.style and
 * stipple_player_set_style, or -1 (bad or taken name, unknown base, a value out of range, or
 * 16 styles already registered; stipple_last_error says which). Not thread-safe. */
int stipple_register_style(const stipple_style_desc* desc);

#ifdef __cplusplus
}
#endif

#endif /* STIPPLE_H */

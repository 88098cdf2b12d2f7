/* `lucent view`: the interactive viewer for tuning translucent materials live (docs/view.md). A
 * GLFW window with a Dear ImGui panel (ui.h) over the renderer of lucent/render.h, on the public API
 * only. Or headless: a script of UI actions (script.c) drives the same state, for tests and
 * benchmarks.
 *
 * Files: app.c (the window, the frame, input, layout, hot reload), render.c (the renderer on a
 * thread of its own), state.c (camera, lights, materials, the background bakes), panel.c (the panel
 * built from the settings table), script.c (playing a script) and script_parse.c (checking one
 * whole, script.h), output.c (saved scenes, screenshots, taps, the reference and its error),
 * trace.c (a progressive trace as the reference). */
#ifndef LUCENT_VIEWER_VIEWER_H
#define LUCENT_VIEWER_VIEWER_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>
#include <time.h>

#include "lucent/lucent.h"

/* What `lucent view` was asked (tools/cmd_view.c). */
typedef struct viewer_options {
    const char *scene;
    const char *const *sets; /* --set overrides */
    int set_count;
    const char *script;    /* --script FILE: play it and quit */
    const char *cache_dir; /* NULL: none */
    bool headless;         /* no window (EGL surfaceless); the script only */
    int width, height;     /* the window (0: the scene's image plus the panel) */
    lucent_pool *pool;
    bool quiet;
} viewer_options;

/* Runs the viewer; returns LUCENT_OK or an error (message set). */
lucent_status viewer_run(const viewer_options *opt);

/* ---- internal ---- */

enum { VIEWER_MAX_MATERIALS = 8, VIEWER_PATH = 1024 };

typedef enum viewer_layout { VIEWER_SINGLE = 0, VIEWER_SPLIT, VIEWER_SIDE } viewer_layout;
typedef enum viewer_show { VIEWER_SHOW_IMAGE = 0, VIEWER_SHOW_ERROR, VIEWER_SHOW_REFERENCE } viewer_show;

/* A bake on a thread of its own: the parts the settings need, for every distinct material, started
 * from copies of the parts already baked so that only what changed is rebuilt. */
typedef struct viewer_job {
    pthread_t thread;
    bool running;     /* started and not yet joined */
    atomic_bool done; /* the thread finished */
    atomic_int step;  /* parts done */
    int steps;        /* parts to do */
    atomic_int at;    /* the material being baked */
    atomic_uint part; /* the part being baked (LUCENT_BAKE_*) */
    double started;   /* lucent_clock_seconds */
    int count;
    lucent_material material[VIEWER_MAX_MATERIALS];
    lucent_baked baked[VIEWER_MAX_MATERIALS];
    lucent_render_settings settings;
    lucent_render_method method_b;
    lucent_material *objects; /* the objects' materials the job is for */
    unsigned what;
    lucent_cache *cache;
    lucent_pool *pool;
    lucent_status status;
    char error[1024];
} viewer_job;

/* A progressive path trace of the scene as it stood when it started, on a thread of its own: each
 * pass of one sample per pixel becomes the reference. */
typedef struct viewer_trace {
    pthread_t thread;
    bool running;     /* started and not yet joined */
    atomic_bool stop; /* asked to stop after the pass under way */
    atomic_bool done; /* the thread finished */
    char *json;       /* the scene it traces */
    char base_dir[VIEWER_PATH];
    lucent_pool *pool;
    pthread_mutex_t lock; /* guards image, spp, seconds, fresh */
    lucent_image *image;  /* the latest estimate, not yet taken */
    uint64_t spp;
    double seconds;
    bool fresh;
    lucent_status status;
    char error[1024];
} viewer_trace;

typedef struct viewer viewer;

/* What the render thread draws next (render.c): copies of the viewer's state. */
typedef struct viewer_request {
    unsigned long gen;                  /* v->gen when it was made */
    int count;                          /* frames: 1 (A) or 2 (A and B) */
    lucent_camera camera[2];            /* A's and B's (side by side: each half's field of view) */
    lucent_render_settings settings[2]; /* sizes included */
    unsigned changed;                   /* LUCENT_RENDERER_LIGHTS | _MATERIALS: read these again */
    int light_count, object_count;
    lucent_light *lights;         /* with LUCENT_RENDERER_LIGHTS */
    lucent_scene_object *objects; /* with LUCENT_RENDERER_MATERIALS: material and albedo */
    int adopt_count;              /* parts baked on the bake thread, to adopt */
    lucent_material adopt_material[VIEWER_MAX_MATERIALS];
    lucent_baked adopt[VIEWER_MAX_MATERIALS];
} viewer_request;

/* A frame the render thread finished. */
typedef struct viewer_frame {
    unsigned long gen;
    int count, width, height;
    lucent_image *image[2]; /* linear RGB radiance of A and B */
    lucent_image *mask;     /* A's coverage */
    uint8_t *rgba[2];       /* as the screen shows them: tonemapped, sRGB-encoded, top row first */
    lucent_frame_times times[2];
    double ms; /* the render thread's time for it */
    lucent_status status;
    char error[1024];
} viewer_frame;

typedef struct viewer_worker {
    pthread_t thread;
    bool running, window;
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    bool started, quit, busy, has_request, has_frame;
    lucent_status start_status;
    char start_error[1024];
    viewer_request request;
    viewer_frame frame;
    unsigned long frames; /* finished */
    lucent_status (*call)(viewer *v, void *arg);
    void *call_arg;
    lucent_status call_status;
    char call_error[1024];
    /* the thread's own */
    lucent_gl_context *gl;
    lucent_scene scene; /* the renderer's: the viewer's, its lights and objects copied */
    lucent_renderer *r;
} viewer_worker;

struct viewer {
    viewer_options opt;
    lucent_scene *scene;
    lucent_camera home;        /* the scene file's camera (reset) */
    lucent_light *home_lights; /* the scene file's lights */
    lucent_gl_context *gl;     /* the window's (the panel and the frames as textures); NULL headless */
    lucent_renderer *r;        /* the render thread's; read here only by lucent_renderer_bakes */
    viewer_worker worker;
    void *window; /* GLFWwindow *, NULL when headless */
    bool ui;      /* the panel is drawn */
    int win_w, win_h;
    int panel_w;

    /* What the UI asks for and what the renderer draws: they differ while a bake runs. */
    lucent_render_settings wanted, applied;
    lucent_render_method method_b, applied_b;
    lucent_material *wanted_material; /* per object */
    bool ready;                       /* the first bake is done */
    viewer_layout layout;
    double split; /* where A ends, as a fraction of the view's width */
    int object, light;

    /* The renderer's bakes as the viewer knows them (what the next job starts from). */
    int baked_count;
    lucent_material baked_material[VIEWER_MAX_MATERIALS];
    lucent_baked baked[VIEWER_MAX_MATERIALS];
    viewer_job job;
    lucent_cache *cache;
    lucent_pool *job_pool;

    /* The last redraw. */
    lucent_frame_times times_a, times_b;
    double redraw_ms, fps, last_frame;
    int frame_w, frame_h; /* the size of A's frame */
    unsigned long gen;    /* counts the changes of what a frame shows */
    unsigned long asked;  /* the gen of the last request handed to the render thread */
    int asked_count;      /* its frames (1: A, 2: A and B) */
    unsigned changed;     /* what the next request must tell the renderer (LUCENT_RENDERER_*) */
    int adopt_count;      /* parts baked, for the next request */
    lucent_material adopt_material[VIEWER_MAX_MATERIALS];
    lucent_baked adopt[VIEWER_MAX_MATERIALS];
    viewer_frame shown;      /* the last finished frame, drawn until the next */
    unsigned frame_tex[2];   /* its textures */
    double frame_ms;         /* how long the render thread took for it */
    double asked_at;         /* when the request in flight was made (lucent_clock_ms) */
    unsigned long ui_frames; /* window frames drawn */
    double slowest_ui_ms;    /* the longest window frame (ui-frames) */
    int keys[64], key_count; /* key presses queued by the GLFW callback, not yet handled */
    bool bake_failed;        /* the last bake failed (scripts exit 1) */
    bool first_failed;       /* the first bake failed: nothing to draw until a change */
    char bake_error[1100];

    /* The reference (lucent trace's EXR) and the error of method A against it. */
    lucent_image *reference;
    char reference_path[VIEWER_PATH];
    bool match_reference; /* render A at the reference's size */
    lucent_image *error_map;
    double rel_rms;
    unsigned long error_gen, ref_gen, error_ref_gen; /* the frame and the reference the error is of */
    viewer_trace trace;
    uint64_t trace_spp; /* of the reference, when it is the progressive trace */
    viewer_show show;
    unsigned show_tex;
    unsigned long show_gen;

    /* The scene file on disk (hot reload). */
    struct timespec mtime;
    double next_check;
    bool hot_reload;
    int reloads; /* scene files reloaded */

    char status[1024];
    bool status_error;
    char save_path[VIEWER_PATH], shot_path[VIEWER_PATH], ref_input[VIEWER_PATH], taps_path[VIEWER_PATH];
    int taps_format;
    char set_form[8192]; /* the last saved scene as --set options */
    bool quit;
};

/* state.c */
lucent_status viewer_scene_open(viewer *v); /* loads opt.scene, (re)creates the renderer */
void viewer_scene_close(viewer *v);
/* Camera moves refuse (LUCENT_ERR_INVALID_ARGUMENT, the camera unchanged) a result that is not
 * finite or puts the camera on its target. */
lucent_status viewer_orbit(viewer *v, double yaw_deg, double pitch_deg);
lucent_status viewer_pan(viewer *v, double dx_px, double dy_px); /* pixels of the view */
lucent_status viewer_zoom(viewer *v, double factor);
void viewer_reset_camera(viewer *v);
lucent_status viewer_light_rotate(viewer *v, int light, double yaw_deg, double pitch_deg);
void viewer_shown_camera(const viewer *v, lucent_camera *dest);          /* A's, as drawn (side by side: wider) */
lucent_status viewer_set(viewer *v, const char *key, const char *value); /* a setting of the table */
lucent_status viewer_method(viewer *v, const char *name, bool b);
lucent_status viewer_material_preset(viewer *v, int object, const char *name);
void viewer_material_edited(viewer *v, int object); /* wanted_material[object] changed */
void viewer_step(viewer *v);                        /* starts, polls and applies the bakes */
void viewer_settle(viewer *v);                      /* waits until the renderer draws what is wanted */
bool viewer_baking(const viewer *v, float *fraction, char *label, size_t size);
lucent_render_settings viewer_frame_settings(const viewer *v, bool b, int width, int height);
void viewer_status(viewer *v, bool error, const char *fmt, ...) LUCENT_PRINTF(3, 4);

/* app.c */
lucent_status viewer_redraw(viewer *v);      /* one window frame: the UI, the last finished frame, swap */
lucent_status viewer_redraw_sync(viewer *v); /* window frames until the render thread drew what is wanted */
void viewer_key_event(viewer *v, int key);   /* a key press, queued (the GLFW callback) */
lucent_status viewer_resize(viewer *v, int width, int height);
void viewer_view_rect(const viewer *v, int rect[4]);

/* panel.c */
void viewer_panel(viewer *v);

/* output.c */
lucent_status viewer_save_scene(viewer *v, const char *path);
lucent_status viewer_scene_text(viewer *v, char **dest); /* the scene as shown, JSON */
lucent_status viewer_screenshot(viewer *v, const char *path);
lucent_status viewer_window_shot(viewer *v, const char *path);
lucent_status viewer_export_taps(viewer *v, const char *path, const char *format);
lucent_status viewer_load_reference(viewer *v, const char *path);
void viewer_drop_reference(viewer *v);
lucent_status viewer_update_error(viewer *v); /* the error map of A against the reference */

/* render.c */
lucent_status viewer_worker_start(viewer *v); /* the render thread and its GL context */
void viewer_worker_stop(viewer *v);
lucent_status viewer_worker_create_renderer(viewer *v); /* for v->scene, waiting for the frame under way */
void viewer_worker_drop_renderer(viewer *v);
bool viewer_worker_submit(viewer *v, viewer_request *q);                /* false while it is busy; q moved when taken */
bool viewer_worker_take(viewer *v, viewer_frame *dest, double wait_ms); /* a finished frame */
bool viewer_worker_busy(viewer *v);
void viewer_request_free(viewer_request *q);
void viewer_frame_free(viewer_frame *f);
lucent_status viewer_to_rgba(const lucent_image *img, const lucent_tonemap_desc *tm, bool encode, uint8_t **dest);

/* trace.c */
lucent_status viewer_trace_start(viewer *v); /* of the scene as it is now, at the frame's size */
void viewer_trace_stop(viewer *v);
void viewer_trace_poll(viewer *v); /* takes a new estimate as the reference */

/* script.c */
lucent_status viewer_script_run(viewer *v, const char *path);

#endif

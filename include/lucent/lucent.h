/* Lucent: rendering translucent materials. This header includes every public module. */
#ifndef LUCENT_H
#define LUCENT_H

#include "lucent/base.h"
#include "lucent/cdrf.h"
#include "lucent/convolve.h"
#include "lucent/engine.h"
#include "lucent/eval.h"
#include "lucent/gltf.h"
#include "lucent/image.h"
#include "lucent/kernel.h"
#include "lucent/material.h"
#include "lucent/mc.h"
#include "lucent/mcml.h"
#include "lucent/mesh.h"
#include "lucent/output.h"
#include "lucent/pack.h"
#include "lucent/profile.h"
#include "lucent/render.h"
#include "lucent/report.h"
#include "lucent/scene.h"
#include "lucent/skin.h"
#include "lucent/spectral.h"
#include "lucent/surfels.h"
#include "lucent/trace.h"

#endif

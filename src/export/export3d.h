/* export/export3d: writers of 3D decompositions; the API is public (include/acd/export.h), this
 * header only ties the module to it. */
#ifndef ACD_EXPORT_EXPORT3D_H
#define ACD_EXPORT_EXPORT3D_H

#include "acd/export.h"

#endif

/*
 * tbasis_mikktspace: mikktspace.c's interface, computed by tbasis. Link libtbasis_mikktspace
 * (-ltbasis_mikktspace) instead of compiling mikktspace.c: a program compiled against
 * mikktspace.h links to it unchanged, statically or dynamically, and gets the same results.
 *
 * This header declares the same ABI as mikktspace.h, for projects that have no copy of it:
 * include one or the other, not both (they define the same types).
 *
 * The contract, for genTangSpaceDefault and genTangSpace alike:
 *
 * - Results. The same return value as mikktspace.c, and the same set callbacks with the same
 *   arguments: per face vertex, tangent, bitangent, fMagS, fMagT, bIsOrientationPreserving (1 or
 *   0) and fSign (1.0f or -1.0f), the same float bits, for triangles and for quads (split as
 *   mikktspace.c splits them), for any fAngularThreshold, and on degenerate and non-finite input.
 *   Where mikktspace.c passes a NaN, so does this library, in the same components; which NaN
 *   (its payload bits) is not fixed.
 *
 * - What is called, in this order, all from the calling thread, during the call only:
 *   1. Nothing, and 0 is returned, when pContext, its m_pInterface, or one of the five get
 *      callbacks (m_getNumFaces to m_getTexCoord) is NULL. The interface is read once, here.
 *   2. m_getNumFaces, once. A count of 0 or less means no face.
 *   3. m_getNumVerticesOfFace, once per face, faces 0, 1, 2, ... in order. Faces of 3 or 4
 *      vertices count; faces of any other count, negative ones included, are ignored.
 *   4. When face 0 has neither 3 nor 4 vertices (and another face has): m_getPosition for
 *      face 0, vertex 0, once, whatever face 0's count, as mikktspace.c reads it to start the
 *      bounding box of its weld. Then, for each face of 3 or 4 vertices in order, for each of its
 *      vertices in order: m_getPosition, m_getNormal, m_getTexCoord, once each. Each call
 *      receives a buffer of 3 floats (2 for the texture coordinate), zeroed, to fill.
 *   5. After the computation, for each face of 3 or 4 vertices in order, for each of its vertices
 *      in order: m_setTSpace, then m_setTSpaceBasic, each only when it is not NULL. With both
 *      NULL the call computes, calls nothing more and returns 1, as mikktspace.c does.
 *   The get callbacks are called fewer times, and in another order, than mikktspace.c calls them;
 *   the set callbacks exactly as it calls them. No callback is called after the call returns, and
 *   none from another thread, whatever tbasis_mikktspace_set_threads says.
 *
 * - Returns 1 after the set callbacks, or 0 with no set callback called: when a callback of
 *   step 1 is NULL, when no face has 3 or 4 vertices, when such a face is numbered above
 *   INT_MAX / 4 (mikktspace.c numbers face vertices 4 * face + vertex in an int, which overflows
 *   past face INT_MAX / 4), when the faces of 3 or 4 vertices have more than INT_MAX / 4 vertices
 *   in all (over 134 million quads; the library's own indices must stay below INT_MAX / 4, where
 *   mikktspace.c's limit is higher), or when memory runs out. Those last two cases are the
 *   departures from mikktspace.c, whose behaviour when memory runs out is undefined (after a
 *   failed weld table it calls the set callbacks with face -1) or differs.
 *
 * - Where mikktspace.c converts a float past int's range to int in its weld's grid (undefined
 *   in C; it happens only when face 0 has neither 3 nor 4 vertices and a corner lies far outside
 *   the box of the others), the library takes the cell mikktspace.c built for x86-64 takes, on
 *   every processor.
 *
 * - A bug in the library (a Rust panic) is caught inside the call, which returns 0; set callbacks
 *   called before it, if any, must then be ignored. The library never unwinds into the caller,
 *   and does not expect a callback to unwind out of it (C++ exceptions included).
 *
 * - Calls on different threads may run at the same time, as mikktspace.c's may: each calls only
 *   its own context's callbacks, from its own thread.
 */

#ifndef TBASIS_MIKKTSPACE_H
#define TBASIS_MIKKTSPACE_H

#ifdef __cplusplus
extern "C" {
#endif

/* mikktspace.h's boolean: 1 true, 0 false. */
typedef int tbool;

typedef struct SMikkTSpaceContext SMikkTSpaceContext;

/* The callbacks, in mikktspace.h's order. iFace counts from 0 below m_getNumFaces(); iVert from
 * 0 below the face's vertex count (3 or 4). The set callbacks may be NULL (either, or both). */
typedef struct {
    /* The number of faces. */
    int (*m_getNumFaces)(const SMikkTSpaceContext *pContext);
    /* The number of vertices of face iFace: 3 and 4 count, other counts are ignored. */
    int (*m_getNumVerticesOfFace)(const SMikkTSpaceContext *pContext, const int iFace);
    /* Write the position (x, y, z) of vertex iVert of face iFace to fvPosOut. */
    void (*m_getPosition)(const SMikkTSpaceContext *pContext, float fvPosOut[], const int iFace, const int iVert);
    /* Write its normal (x, y, z) to fvNormOut. */
    void (*m_getNormal)(const SMikkTSpaceContext *pContext, float fvNormOut[], const int iFace, const int iVert);
    /* Write its texture coordinate (u, v) to fvTexcOut. */
    void (*m_getTexCoord)(const SMikkTSpaceContext *pContext, float fvTexcOut[], const int iFace, const int iVert);
    /* Receives its unit tangent (x, y, z) and fSign, 1.0f or -1.0f:
     * bitangent = fSign * cross(normal, tangent). */
    void (*m_setTSpaceBasic)(const SMikkTSpaceContext *pContext, const float fvTangent[], const float fSign,
                             const int iFace, const int iVert);
    /* Receives its unit tangent and unit bitangent (both in the normal's plane, not necessarily
     * perpendicular to each other), the magnitudes of dP/ds and dP/dt, and whether the texture
     * mapping preserves orientation (1: fSign 1.0f; 0: fSign -1.0f). */
    void (*m_setTSpace)(const SMikkTSpaceContext *pContext, const float fvTangent[], const float fvBiTangent[],
                        const float fMagS, const float fMagT, const tbool bIsOrientationPreserving,
                        const int iFace, const int iVert);
} SMikkTSpaceInterface;

struct SMikkTSpaceContext {
    /* The callbacks. */
    SMikkTSpaceInterface *m_pInterface;
    /* Yours: the callbacks receive the context and read it. */
    void *m_pUserData;
};

/* genTangSpace(pContext, 180.0f): no angular threshold. */
tbool genTangSpaceDefault(const SMikkTSpaceContext *pContext);

/* A tangent space for every vertex of every face of 3 or 4 vertices, handed to the set
 * callbacks (the contract above). Within a smooth group, faces whose tangents or bitangents lie
 * more than fAngularThreshold degrees apart get separate tangent spaces. 1 on success, 0 with no
 * set callback called otherwise. */
tbool genTangSpace(const SMikkTSpaceContext *pContext, const float fAngularThreshold);

/* The worker threads of the calls that start after this one, in the whole process: 1 (the
 * default, as mikktspace.c) or less, the calling thread alone. Results are the same on any count;
 * callbacks always run on the calling thread. Each call reads the count once, when it starts, so a
 * call already running keeps its count, and calls running at the same time each use up to this
 * many workers. With more than 1, the standard library's bookkeeping to start a worker thread (a
 * few dozen bytes per thread) is the one allocation that cannot fail softly: the process ends
 * there, where with 1 a call returns 0 when memory runs out. Not in mikktspace.h: declare it, or
 * include this header, to use it. */
void tbasis_mikktspace_set_threads(int threads);

#ifdef __cplusplus
}
#endif

#endif /* TBASIS_MIKKTSPACE_H */

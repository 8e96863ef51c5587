// SPDX-License-Identifier: BSD-3-Clause
// The plugin's client-side watchers (vtkBrumeCameraFollower,
// vtkBrumeRenderViewInitializationHelper) follow every session of the
// process, those open now and those connected later.
#ifndef vtkBrumeSessions_h
#define vtkBrumeSessions_h

#include "vtkBrumeParaViewRepresentationModule.h" // For export macro

class vtkSMSession;

/**
 * Calls `watch` for each session the process has, and for each session it
 * connects later. False (nothing done) where the process has no server
 * manager. Each `watch` must tolerate being called twice for one session.
 */
VTKBRUMEPARAVIEWREPRESENTATION_EXPORT bool vtkBrumeWatchSessions(void (*watch)(vtkSMSession*));

#endif

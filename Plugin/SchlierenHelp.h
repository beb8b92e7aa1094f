#ifndef SchlierenHelp_h
#define SchlierenHelp_h
// The plugin's help pages where ParaView's own plugin macro leaves them out (5.12 and 5.13 built
// with Qt 6; Plugin/SchlierenHelp.cmake builds the .qch): registers the embedded Schlieren.qch
// (namespace Schlieren.org) with the GUI's help engine, so that the "?" button of a Schlieren
// proxy's panel and Help show its page. Called once, when the toolbar is made; returns whether the
// documentation is registered. Elsewhere ParaView registers the plugin's .qch itself.
bool SchlierenRegisterHelp();
#endif

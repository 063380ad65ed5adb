{{header}}#version 3.7;
global_settings { assumed_gamma 1.0 ambient_light 0{{trace_level}} }  // linear: render with File_Gamma=1.0

#ifndef (Facet_Light) #declare Facet_Light = -1; #end        // -1: every light; i: light i alone
#ifndef (Facet_Exposure) #declare Facet_Exposure = 1; #end  // scales every radiance (keeps PNGs below 1)
#declare Facet_Passes = {{passes}};  // renders with Facet_Light = 0 … {{last}} sum to the exact image

// facet's world is right-handed: the negative right vector makes POV-Ray's camera right-handed too.
camera {
{{camera}}}

{{body}}
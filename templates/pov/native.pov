// ---- Lights (POV-Ray's attenuation is the catalog's law here)
{{lights}}
// ---- Objects
{{objects}}
// ---- Lights: the radiance of each light of unit colour, per material and object
{{functions}}{{objects}}

// One pass at a time is exact: Facet_Light = i renders light i alone (or, after
// the lights, the emission m_a ⊗ A + m_e); the passes sum to the image.
#if (Facet_Light >= 0)
#switch (Facet_Light)
{{cases}}#end
#else
// Every pass at once: nested copies, one light_group each, the inner ones inset.
{{copies}}#end

// Depth only: the rasteriser writes the depth; no colour.
void main()
{
}

#version 450 core
// Fills the frame with one colour.
uniform vec4 uColour;
in vec2 vUv;
out vec4 fragColour;
void main() { fragColour = uColour; }

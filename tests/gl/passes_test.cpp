// The frame as passes: every pass leaves the GL state as it found it, depth
// comes out linear, and cameras frame the terrain whatever the view.

#include "GlTest.h"

#include <sierra/gpu/GlStateScope.h>
#include <sierra/gpu/Program.h>
#include <sierra/render/Camera.h>
#include <sierra/render/Capture.h>
#include <sierra/render/FrameTarget.h>
#include <sierra/render/TerrainGpu.h>
#include <sierra/render/TerrainRenderer.h>
#include <sierra/terrain/DiamondSquare.h>
#include <sierra/terrain/HeightfieldIO.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace sierra;

namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

class Passes : public test::GlTest {
  protected:
    void SetUp() override { createContext(kWidth, kHeight); }
};

// Share of pixels that differ from the sky colour by more than a few levels.
double terrainShare(const gpu::Image& image, glm::vec3 sky) {
    int64_t terrain = 0;
    for (size_t p = 0; p < image.rgba.size(); p += 4) {
        glm::vec3 c(image.rgba[p], image.rgba[p + 1], image.rgba[p + 2]);
        terrain += glm::length(c - sky * 255.0f) > 6.0f;
    }
    return double(terrain) / double(image.width * image.height);
}

// A state no pass would leave behind by accident: blending, culling, odd
// alignments, textures on the units the passes use, a uniform buffer bound.
void setUnusualState(gpu::Texture& texture, gpu::Buffer& buffer) {
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glDepthFunc(GL_GREATER);
    glDisable(GL_DEPTH_TEST);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPolygonOffset(3.0f, 5.0f);
    glActiveTexture(GL_TEXTURE3);
    glBindTextureUnit(0, texture.id());
    glBindTextureUnit(1, texture.id());
    glBindTextureUnit(2, texture.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, buffer.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, buffer.id());
    glClearColor(0.1f, 0.2f, 0.3f, 0.4f);
}

TEST_F(Passes, EveryPassRestoresTheGlState) {
    terrain::Heightfield field = terrain::generateDiamondSquare({.size = 65, .seed = 3});
    field.setVerticalScale(0.2f * 64.0f /
                           std::max(field.range().second - field.range().first, 1e-3f));
    auto terrain = render::TerrainRenderer::create({.field = &field, .seaLevel = 0.0f});
    auto target = render::FrameTarget::create({.width = kWidth, .height = kHeight, .samples = 4});
    gpu::Texture texture = gpu::Texture::create({.width = 4, .height = 4});
    gpu::Buffer buffer = gpu::Buffer::create({.size = 256});
    render::Camera camera = render::defaultCamera(terrain.bounds(), float(kWidth) / kHeight);

    target.begin(render::TerrainRenderer::clearColour({}));
    setUnusualState(texture, buffer);
    gpu::GlState before = gpu::GlState::capture();
    for (render::Lod lod : {render::Lod::Sbt, render::Lod::Full}) {
        terrain.draw(camera, kWidth, kHeight, {.lod = lod, .wireframe = true});
        gpu::GlState after = gpu::GlState::capture();
        EXPECT_EQ(before.differences(after), "")
            << "after the frame's passes, lod " << render::lodName(lod);
        terrain.renderDepth(camera, kWidth, kHeight, {.lod = lod});
        after = gpu::GlState::capture();
        EXPECT_EQ(before.differences(after), "")
            << "after the depth pass, lod " << render::lodName(lod);
    }
}

TEST_F(Passes, StateCaptureSeesEveryChange) {
    // The check above is only as good as the capture: a change must show.
    gpu::GlState a = gpu::GlState::capture();
    glEnable(GL_BLEND);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    gpu::Texture texture = gpu::Texture::create({.width = 2, .height = 2});
    glBindTextureUnit(5, texture.id());
    gpu::GlState b = gpu::GlState::capture();
    std::string diff = a.differences(b);
    EXPECT_NE(diff.find("BLEND"), std::string::npos) << diff;
    EXPECT_NE(diff.find("pack alignment"), std::string::npos) << diff;
    EXPECT_NE(diff.find("texture unit 5"), std::string::npos) << diff;
    a.restore();
    EXPECT_EQ(a.differences(gpu::GlState::capture()), "");
}

TEST_F(Passes, AProgramDeletedWhileCurrentIsNotRestored) {
    // GL keeps a program deleted while it is current until another one is
    // used; a pass in between uses its own, so the name is gone by the time
    // the scope ends and binding it again would be GL_INVALID_VALUE (the
    // KHR_debug check of GlTest fails the test on any error).
    const GLuint deleted =
        gpu::Program::create({.vertex = "solid.vert", .fragment = "solid.frag"}).release();
    glUseProgram(deleted);
    glDeleteProgram(deleted);
    ASSERT_TRUE(glIsProgram(deleted));  // flagged, still current
    gpu::Program other = gpu::Program::create({.vertex = "solid.vert", .fragment = "solid.frag"});
    {
        gpu::GlStateScope scope;
        glUseProgram(other.id());
        EXPECT_FALSE(glIsProgram(deleted));  // no longer current: gone
    }
    GLint current = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    EXPECT_EQ(current, 0);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    // A live program is restored as before.
    glUseProgram(other.id());
    {
        gpu::GlStateScope scope;
        glUseProgram(0);
    }
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    EXPECT_EQ(GLuint(current), other.id());
    glUseProgram(0);
}

TEST_F(Passes, ObjectsDeletedInsideAScopeStayUnbound) {
    // Deleting a bound texture, buffer, vertex array or framebuffer unbinds it
    // (GL does, from every binding of the context); the scope's end must not
    // bind the dead names again (an error the KHR_debug check of GlTest fails
    // the test on), and objects still alive are bound again as before.
    gpu::Texture kept = gpu::Texture::create({.width = 2, .height = 2});
    GLuint texture = 0, buffer = 0, vertexArray = 0, framebuffer = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, 2, 2);
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, 256, nullptr, GL_STATIC_DRAW);
    glCreateVertexArrays(1, &vertexArray);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    glBindTextureUnit(2, texture);
    glBindTextureUnit(4, kept.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBindVertexArray(vertexArray);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    const gpu::GlState before = gpu::GlState::capture();
    {
        gpu::GlStateScope scope;
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteVertexArrays(1, &vertexArray);
        glDeleteBuffers(1, &buffer);
        glDeleteTextures(1, &texture);
        glBindTextureUnit(4, 0);
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    gpu::GlState after = gpu::GlState::capture();
    EXPECT_EQ(after.textures[2][1], 0);
    EXPECT_EQ(after.textures[4][1], GLint(kept.id()));
    EXPECT_EQ(after.uniformBindings[1], 0);
    EXPECT_EQ(after.uniformBuffer, 0);
    EXPECT_EQ(after.arrayBuffer, 0);
    EXPECT_EQ(after.vertexArray, 0);
    EXPECT_EQ(after.readFramebuffer, 0);
    // Everything else is as it was.
    after.textures[2][1] = before.textures[2][1];
    after.uniformBindings[1] = before.uniformBindings[1];
    after.uniformBuffer = before.uniformBuffer;
    after.arrayBuffer = before.arrayBuffer;
    after.vertexArray = before.vertexArray;
    after.readFramebuffer = before.readFramebuffer;
    EXPECT_EQ(before.differences(after), "");
    glBindTextureUnit(4, 0);
}

TEST_F(Passes, DepthOfAFlatTerrainSeenFromAboveIsItsHeight) {
    terrain::Heightfield field(129, 129, 0.0f);
    auto terrain = render::TerrainRenderer::create({.field = &field});
    const float height = 40.0f;
    render::Camera camera;
    camera.position = {64.0f, height, 64.0f};
    camera.target = {64.0f, 0.0f, 64.0f};
    render::fitClipPlanes(camera, terrain.bounds());
    for (render::Lod lod : {render::Lod::Sbt, render::Lod::Full}) {
        render::DepthImage depth = terrain.renderDepth(camera, kWidth, kHeight, {.lod = lod});
        ASSERT_EQ(depth.depth.size(), size_t(kWidth) * kHeight);
        int64_t terrainPixels = 0;
        float worst = 0.0f;
        for (float d : depth.depth) {
            if (std::isnan(d)) continue;
            ++terrainPixels;
            worst = std::max(worst, std::abs(d - height) / height);
        }
        // The 128-unit square fills the 45-degree view from 40 units up.
        EXPECT_EQ(terrainPixels, int64_t(kWidth) * kHeight) << render::lodName(lod);
        EXPECT_LE(worst, 1e-3f) << render::lodName(lod);
    }
    // Looking past the terrain: NaN where there is none.
    camera.position = {64.0f, 10.0f, 300.0f};
    camera.target = {64.0f, 10.0f, 200.0f};
    render::fitClipPlanes(camera, terrain.bounds());
    render::DepthImage away = terrain.renderDepth(camera, kWidth, kHeight, {});
    EXPECT_TRUE(std::isnan(away.depth[0]));
}

// The projected NDC position of p.
glm::vec3 project(const render::Camera& camera, float aspect, glm::vec3 p) {
    glm::vec4 clip = camera.viewProjection(aspect) * glm::vec4(p, 1.0f);
    return glm::vec3(clip) / clip.w;
}

TEST_F(Passes, DefaultAndOrbitCamerasFrameEveryTerrainCorner) {
    // A non-square DEM: 403 x 344 samples, 30 m apart, 236..1076 m high.
    render::SceneBounds dem{{0.0f, 236.0f, 0.0f}, {402.0f * 30.0f, 1076.0f, 343.0f * 30.0f}};
    render::SceneBounds square{{0.0f, -20.0f, 0.0f}, {1024.0f, 180.0f, 1024.0f}};
    for (const render::SceneBounds& b : {dem, square}) {
        for (float aspect : {1.0f, 16.0f / 9.0f, 9.0f / 16.0f}) {
            std::vector<render::Camera> cameras = render::orbitPath(b, 12, aspect);
            cameras.push_back(render::defaultCamera(b, aspect));
            for (const render::Camera& c : cameras)
                for (const glm::vec3& corner : b.corners()) {
                    glm::vec3 ndc = project(c, aspect, corner);
                    EXPECT_LE(std::abs(ndc.x), 1.0f) << "aspect " << aspect;
                    EXPECT_LE(std::abs(ndc.y), 1.0f) << "aspect " << aspect;
                    EXPECT_LE(std::abs(ndc.z), 1.0f) << "a corner is clipped by near or far";
                }
            // Framed, not lost in the distance: some corner comes near the edge.
            float widest = 0.0f;
            for (const glm::vec3& corner : b.corners()) {
                glm::vec3 ndc = project(cameras.back(), aspect, corner);
                widest = std::max({widest, std::abs(ndc.x), std::abs(ndc.y)});
            }
            EXPECT_GT(widest, 0.9f);
        }
    }
}

class Views : public Passes {
  protected:
    void SetUp() override {
        Passes::SetUp();
        field_ = terrain::generateDiamondSquare({.size = 129, .seed = 7});
        auto [lo, hi] = field_.range();
        field_.setVerticalScale(0.2f * 128.0f / (hi - lo));
        terrain_.emplace(render::TerrainRenderer::create({.field = &field_}));
        target_.emplace(render::FrameTarget::create({.width = kWidth, .height = kHeight}));
    }
    double terrainShareOf(const render::Camera& camera, const std::string& name) {
        target_->begin(render::TerrainRenderer::clearColour({}));
        render::DrawStats stats =
            terrain_->draw(camera, kWidth, kHeight, {.lighting = {.fogDensity = 0.0f}});
        gpu::Image image = target_->read();
        render::writePng(std::string(SIERRA_TEST_OUTPUT_DIR) + "/view_" + name + ".png", image);
        EXPECT_GT(stats.triangles, 0u) << name;
        return terrainShare(image, render::Lighting{}.sky);
    }
    terrain::Heightfield field_;
    std::optional<render::TerrainRenderer> terrain_;
    std::optional<render::FrameTarget> target_;
};

TEST_F(Views, NadirOrthographicAndDistantCamerasSeeTerrain) {
    render::SceneBounds b = terrain_->bounds();
    float aspect = float(kWidth) / kHeight;
    glm::vec3 centre = b.centre();

    render::Camera nadir;  // straight down, close enough that the terrain fills the view
    nadir.position = {centre.x, b.max.y + 60.0f, centre.z};
    nadir.target = {centre.x, b.min.y, centre.z};
    render::fitClipPlanes(nadir, b);
    EXPECT_GT(terrainShareOf(nadir, "nadir"), 0.95);

    render::Camera ortho = render::framedCamera(b, {.target = centre,
                                                    .azimuthDeg = 0.0f,
                                                    .elevationDeg = 90.0f,
                                                    .projection = render::Projection::Orthographic,
                                                    .aspect = aspect});
    ortho.orthoHeight *= 0.5f;  // zoomed in: the square covers the frame
    EXPECT_GT(terrainShareOf(ortho, "ortho_nadir"), 0.95);

    // Ten times the extent away, through a long lens: near and far follow the
    // terrain, so the frame is not emptied by a fixed far plane.
    float extent = std::max(b.size().x, b.size().z);
    render::Camera distant = render::framedCamera(b, {.target = centre,
                                                      .elevationDeg = 35.0f,
                                                      .fovYDegrees = 4.0f,
                                                      .aspect = aspect,
                                                      .distance = 10.0f * extent});
    distant.fovYDegrees = 2.0f;  // narrower than the framing: the terrain overfills the frame
    EXPECT_GT(terrainShareOf(distant, "distant"), 0.5);
}

TEST_F(Views, OrthographicTauStillMeansPixels) {
    // Orthographic lambda is pixels per world unit: halving the view height
    // doubles it, so the mesh refines as the terrain grows on screen.
    render::SceneBounds b = terrain_->bounds();
    render::Camera ortho = render::framedCamera(b, {.target = b.centre(),
                                                    .elevationDeg = 90.0f,
                                                    .projection = render::Projection::Orthographic,
                                                    .aspect = float(kWidth) / kHeight});
    EXPECT_FLOAT_EQ(ortho.lambda(kHeight), float(kHeight) / ortho.orthoHeight);
    target_->begin(render::TerrainRenderer::clearColour({}));
    uint64_t wide = terrain_->draw(ortho, kWidth, kHeight, {.cull = false}).triangles;
    ortho.orthoHeight *= 0.25f;
    uint64_t zoomed = terrain_->draw(ortho, kWidth, kHeight, {.cull = false}).triangles;
    EXPECT_GT(zoomed, wide);
}

}  // namespace

// The largest grid is a 2^n+1 side whose textures this GL takes, and the next
// one (2 side - 1) it does not, unless the loaders' own budget stops first.
TEST_F(Passes, MaxGridSideFollowsTheTextureLimit) {
    GLint maxTexture = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTexture);
    const int side = render::TerrainGpu::maxGridSide();
    EXPECT_EQ((side - 1) & (side - 2), 0) << side;
    EXPECT_LE(side, maxTexture);
    EXPECT_LE(side, terrain::kDefaultMaxPaddedSide);
    EXPECT_TRUE(2 * side - 1 > maxTexture || side == terrain::kDefaultMaxPaddedSide) << side;
}
